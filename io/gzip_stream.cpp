#include "io/gzip_stream.hpp"

#include <array>

#include "io/input_error.hpp"

namespace msislab::io {

// windowBits 15 + 16 asks zlib for a gzip header and trailer instead of a raw zlib stream.
GzipStream::GzipStream(std::ostream& out, const std::string& path, bool compress)
    : out_(out), path_(path), compress_(compress) {
  if (compress_ &&
      deflateInit2(&zs_, Z_DEFAULT_COMPRESSION, Z_DEFLATED, 15 + 16, 8, Z_DEFAULT_STRATEGY) != Z_OK)
    fail_file(path_, "cannot start gzip compression");
}

GzipStream::~GzipStream() {
  if (compress_) deflateEnd(&zs_);
}

void GzipStream::write(std::string_view text) {
  if (!compress_) {
    out_.write(text.data(), static_cast<std::streamsize>(text.size()));
    return;
  }
  deflate_all(text, Z_NO_FLUSH);
}

void GzipStream::finish() {
  if (compress_) deflate_all({}, Z_FINISH);
}

// zlib's zpipe pattern: run deflate until it leaves room in the output buffer, i.e. it has
// consumed all input (and, with Z_FINISH, written the trailer).
void GzipStream::deflate_all(std::string_view text, int flush) {
  std::array<char, 1 << 16> buffer;
  zs_.next_in = reinterpret_cast<Bytef*>(const_cast<char*>(text.data()));
  zs_.avail_in = static_cast<uInt>(text.size());
  do {
    zs_.next_out = reinterpret_cast<Bytef*>(buffer.data());
    zs_.avail_out = static_cast<uInt>(buffer.size());
    if (deflate(&zs_, flush) == Z_STREAM_ERROR) fail_file(path_, "gzip compression failed");
    out_.write(buffer.data(), static_cast<std::streamsize>(buffer.size() - zs_.avail_out));
  } while (zs_.avail_out == 0);
}

}  // namespace msislab::io
