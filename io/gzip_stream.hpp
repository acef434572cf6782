// Writes text to a std::ostream either as is or gzip-compressed (zlib deflate with a gzip
// wrapper), so that gzip output can go through write_file_atomically like every other writer.
#pragma once

#include <zlib.h>

#include <ostream>
#include <string>
#include <string_view>

namespace msislab::io {

class GzipStream {
 public:
  /// compress = false passes the text through unchanged. path only names errors.
  GzipStream(std::ostream& out, const std::string& path, bool compress);
  ~GzipStream();
  GzipStream(const GzipStream&) = delete;
  GzipStream& operator=(const GzipStream&) = delete;

  void write(std::string_view text);
  /// Ends the gzip stream; call once after the last write.
  void finish();

 private:
  void deflate_all(std::string_view text, int flush);

  std::ostream& out_;
  const std::string& path_;
  bool compress_;
  z_stream zs_{};
};

}  // namespace msislab::io
