// PNG files drawn with OpenCV: encoded, signed as msislab's own (io::signed_png) and written
// atomically.
#pragma once

#include <opencv2/core.hpp>
#include <string>

namespace msislab::io {

/// Encodes `image` as PNG and writes it to `path`; InputError naming the path on failure.
void write_png(const std::string& path, const cv::Mat& image);

}  // namespace msislab::io
