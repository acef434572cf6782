// The sonar readings of a dataset, beam by beam: segmented from the raw *_IS.log, or chosen from
// the detected bins of *_detections.csv[.gz] with the beam times of *_IS_timestamps.log.
#pragma once

#include "dataset/dataset.hpp"
#include "dataset/truth.hpp"
#include "geometry/calibration.hpp"
#include "io/detections.hpp"
#include "io/stpere_logs.hpp"
#include "slam/beam_segmentation.hpp"
#include "slam/scan_sequence.hpp"

namespace msislab::dataset {

struct SonarInput {
  std::vector<BeamReadings> beams;  ///< every beam in time order, with or without readings
  int beams_per_revolution = 200;
  std::string source;  ///< "IS log" or "detections"
};

/// Throws io::InputError when the dataset has neither a raw log nor detections with beam times.
SonarInput load_sonar_readings(const DatasetFiles& files, const Calibration& calibration,
                               const SegmentationConfig& segmentation);

/// The same for a run's dataset, from its files or, held in memory, its records.
SonarInput load_sonar_readings(const RunInputs& in);
/// Whether the dataset has any sonar data (a raw log or detections).
bool has_sonar_data(const RunInputs& in);

/// The readings of every beam of the beam times, chosen from the detected bins (rows in beam_row
/// order) with segment_detections: what load_sonar_readings does with a dataset's detections, for
/// a caller that has read them already. Throws io::InputError naming files.detections when a
/// beam_row is not a row of the times.
SonarInput readings_from_detections(const DatasetFiles& files,
                                    const std::vector<io::BeamTimeRecord>& times,
                                    const std::vector<io::DetectionRecord>& rows,
                                    const io::SonarSetup& setup, const SonarMount& mount,
                                    const SegmentationConfig& segmentation);

}  // namespace msislab::dataset
