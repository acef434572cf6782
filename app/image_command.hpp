// `msislab image DATASET_DIR --out PNG [--revolution K] [--size PX]`: the acoustic image of one
// revolution of the raw sonar log.
#pragma once

#include <string>

namespace msislab::app {

struct ImageOptions {
  std::string dataset_dir;
  std::string out_path;
  int revolution = 0;  ///< 0-based: beams [K x steps, (K + 1) x steps)
  int size_px = 800;
};

/// Throws io::InputError on bad input (no *_IS.log, revolution past the end).
void draw_image(const ImageOptions& options);

}  // namespace msislab::app
