// A dataset directory, real or synthetic (docs/formats.md): its files found by suffix, and the
// navigation and truth streams loaded through the calibration.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "slam/calibration.hpp"
#include "slam/evaluation.hpp"
#include "slam/navigation.hpp"

namespace msislab::io {

struct DatasetFiles {
  std::string dir;
  std::optional<std::string> dvl;               ///< *_DVL.log
  std::optional<std::string> mti;               ///< *_MTi.log
  std::optional<std::string> gps;               ///< *_DGPS.log
  std::optional<std::string> setup;             ///< *_SETUP.log
  std::optional<std::string> is_log;            ///< *_IS.log
  std::optional<std::string> beam_times;        ///< *_IS_timestamps.log
  std::optional<std::string> detections;        ///< *_detections.csv or *_detections.csv.gz
  std::optional<std::string> calibration;       ///< calibration.yaml
  std::optional<std::string> truth_trajectory;  ///< truth/trajectory.tum
  std::optional<std::string> truth_beams;       ///< truth/beams.csv
  std::optional<std::string> truth_segments;    ///< truth/segments.csv
};

/// Finds the files of a dataset directory. Throws InputError if the directory does not exist or a
/// suffix matches more than one file.
DatasetFiles find_dataset_files(const std::string& dir);

/// The named time windows of a simulated dataset (truth/segments.csv, `name,begin_s,end_s`: the
/// scenario's `segments`, in seconds from the first truth stamp); empty when the file is absent.
/// Throws InputError on a malformed row, an empty or repeated name, or end_s <= begin_s.
std::vector<TimeSegment> load_truth_segments(const DatasetFiles& files);

/// calibration.yaml when present, else the St. Pere calibration.
Calibration load_calibration(const DatasetFiles& files);

/// DVL (rows with bottom lock) and heading, in the vehicle frame through the calibration.
/// Requires the DVL and MTi logs.
NavigationLog load_navigation(const DatasetFiles& files, const Calibration& calibration);

/// GPS fixes (status > 0) in the local frame. Requires the GPS log.
std::vector<PositionFix> load_gps_fixes(const DatasetFiles& files, const Calibration& calibration);

}  // namespace msislab::io
