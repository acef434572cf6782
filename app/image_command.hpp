// `msislab image DATASET_DIR --out PNG [--revolution K] [--size PX]`: the acoustic image of one
// revolution of the raw sonar log.
#pragma once

#include <string>
#include <vector>

#include "geometry/calibration.hpp"
#include "io/stpere_logs.hpp"

namespace msislab::app {

struct ImageOptions {
  std::string dataset_dir;
  std::string out_path;
  int revolution = 0;  ///< 0-based: beams [K x steps, (K + 1) x steps)
  int size_px = 800;
};

/// Throws io::InputError on bad input (no *_IS.log, revolution past the end).
void draw_image(const ImageOptions& options);

/// One revolution of a dataset's raw sonar log, with what drawing it needs.
struct SonarRevolution {
  std::string dataset_dir;
  int index = 0;  ///< 0-based
  std::vector<io::SonarBeamRecord> beams;
  io::SonarSetup setup;
  SonarMount mount;
};

/// Revolution K of the dataset's *_IS.log; K < 0 picks the middle one. Throws io::InputError when
/// there is no *_IS.log or K is past the end.
SonarRevolution read_revolution(const std::string& dataset_dir, int revolution);

}  // namespace msislab::app
