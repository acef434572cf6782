// `msislab image DATASET_DIR --out PNG [--revolution K | --keyframe K] [--size PX]`: the acoustic
// image of one revolution of the raw sonar log, or of one keyframe of the detections file (the
// real St. Pere data have only that), drawn the same way.
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
  int keyframe = 0;    ///< > 0: keyframe K (1-based) of *_detections.csv[.gz] instead
  int size_px = 800;
};

/// Throws io::InputError on bad input (no *_IS.log or detections, revolution or keyframe past
/// the end).
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

/// Keyframe K (1-based, as in the file) of the dataset's *_detections.csv[.gz]: a beam for every
/// beam with a detection, its detected bins at full intensity (255) and the rest 0, so the fan
/// shows what the detector kept. Throws io::InputError when there are no detections or no
/// keyframe K.
SonarRevolution read_detected_revolution(const std::string& dataset_dir, int keyframe);

}  // namespace msislab::app
