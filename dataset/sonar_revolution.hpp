// One revolution of a dataset's sonar, with what drawing it as an acoustic image needs
// (plot/acoustic_image.hpp): the beams of the raw *_IS.log, or one keyframe of the detections drawn
// the same way (the real St. Pere data have only that). `msislab image` and `msislab plot` read it.
#pragma once

#include <string>
#include <vector>

#include "geometry/calibration.hpp"
#include "io/stpere_logs.hpp"

namespace msislab::dataset {

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

}  // namespace msislab::dataset
