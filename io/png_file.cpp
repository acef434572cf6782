#include "io/png_file.hpp"

#include <opencv2/imgcodecs.hpp>
#include <vector>

#include "io/atomic_file.hpp"
#include "io/input_error.hpp"
#include "io/output_guard.hpp"

namespace msislab::io {

void write_png(const std::string& path, const cv::Mat& image) {
  std::vector<unsigned char> png;
  if (!cv::imencode(".png", image, png)) fail_file(path, "PNG encoding failed");
  png = signed_png(std::move(png));
  write_file_atomically(path, [&](std::ostream& out) {
    out.write(reinterpret_cast<const char*>(png.data()), static_cast<std::streamsize>(png.size()));
  });
}

}  // namespace msislab::io
