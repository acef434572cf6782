// A dataset directory, real or synthetic (docs/formats.md): its files found by suffix, and the
// navigation and truth streams loaded through the calibration.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "eval/evaluation.hpp"
#include "geometry/calibration.hpp"
#include "geometry/navigation_noise.hpp"
#include "io/detections.hpp"
#include "io/stpere_logs.hpp"
#include "io/tum.hpp"
#include "slam/navigation.hpp"

namespace msislab::dataset {

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
  std::optional<std::string> navigation_noise;  ///< navigation_noise.yaml (simulated datasets)
  std::optional<std::string> truth_trajectory;  ///< truth/trajectory.tum
  std::optional<std::string> truth_beams;       ///< truth/beams.csv
  std::optional<std::string> truth_segments;    ///< truth/segments.csv
};

/// A dataset held in memory as the records its files would store, so that a simulation can be
/// handed straight to the methods (`msislab montecarlo`) and they see the same numbers as from the
/// directory. `name` stands for the directory in messages.
struct DatasetRecords {
  std::string name;
  Calibration calibration;  ///< as stored (calibration_as_stored)
  /// The scenario's navigation noise, as stored (navigation_noise_as_stored); absent: none stated.
  std::optional<NavigationNoise> navigation_noise;
  std::vector<io::DvlRecord> dvl;
  std::vector<io::MtiRecord> mti;
  std::vector<io::GpsRecord> gps;  ///< empty: no *_DGPS.log
  io::SonarSetup setup;
  std::vector<io::SonarBeamRecord> is_log;     ///< empty: no *_IS.log
  std::vector<io::BeamTimeRecord> beam_times;  ///< empty: no *_IS_timestamps.log
  std::vector<io::DetectionRecord> detections;
  bool has_detections = false;
  std::vector<io::TumPose> truth_trajectory;  ///< yaw as stored (yaw_as_stored); empty: no truth
  std::vector<TimeSegment> truth_segments;
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

/// The same from the logs' records.
NavigationLog navigation_of(const std::vector<io::DvlRecord>& dvl,
                            const std::vector<io::MtiRecord>& mti, const Calibration& calibration);

/// GPS fixes (status > 0) in the local frame. Requires the GPS log.
std::vector<PositionFix> load_gps_fixes(const DatasetFiles& files, const Calibration& calibration);
/// The same from the log's records.
std::vector<PositionFix> gps_fixes_of(const std::vector<io::GpsRecord>& rows,
                                      const Calibration& calibration);

}  // namespace msislab::dataset
