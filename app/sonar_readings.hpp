// The sonar readings of a dataset, beam by beam: segmented from the raw *_IS.log, or chosen from
// the detected bins of *_detections.csv[.gz] with the beam times of *_IS_timestamps.log.
#pragma once

#include "io/dataset.hpp"
#include "slam/beam_segmentation.hpp"
#include "slam/calibration.hpp"
#include "slam/scan_sequence.hpp"

namespace msislab::app {

struct SonarInput {
  std::vector<BeamReadings> beams;  ///< every beam in time order, with or without readings
  int beams_per_revolution = 200;
  std::string source;  ///< "IS log" or "detections"
};

/// Throws io::InputError when the dataset has neither a raw log nor detections with beam times.
SonarInput load_sonar_readings(const io::DatasetFiles& files, const Calibration& calibration,
                               const SegmentationConfig& segmentation);

}  // namespace msislab::app
