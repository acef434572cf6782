// `msislab image DATASET_DIR --out PNG [--revolution K | --keyframe K] [--size PX]`: the acoustic
// image of one revolution of the raw sonar log, or of one keyframe of the detections file (the
// real St. Pere data have only that), drawn the same way.
#pragma once

#include <string>

namespace msislab::app {

struct ImageOptions {
  std::string dataset_dir;
  std::string out_path;
  int revolution = 0;  ///< 0-based: beams [K x steps, (K + 1) x steps)
  int keyframe = 0;    ///< > 0: keyframe K (1-based) of *_detections.csv[.gz] instead
  int size_px = 800;
};

/// Throws io::InputError on bad input (no *_IS.log or detections, revolution or keyframe past
/// the end).
void draw_image(const ImageOptions& options);

}  // namespace msislab::app
