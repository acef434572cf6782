// The truth of a dataset: simulation truth (truth/trajectory.tum) when present, else the GPS log.
#pragma once

#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "dataset/dataset.hpp"
#include "eval/evaluation.hpp"
#include "slam/navigation.hpp"
#include "slam/slam_config.hpp"

namespace msislab::dataset {

struct Truth {
  std::string kind;  ///< "simulation", "gps" or empty when the dataset has none
  std::vector<PositionFix> positions;
  std::vector<StampedPose> poses;  ///< simulation truth only (GPS has no heading)
  double depth_m = 0.0;            ///< vehicle depth for the TUM z (0 when unknown)
};

Truth load_truth(const DatasetFiles& files, const Calibration& calibration);

/// Pose truth from a TUM file (the simulation's truth/trajectory.tum, or a file given to
/// `msislab eval --truth`), recorded as `kind`.
Truth read_tum_truth(const std::string& path, const std::string& kind);
/// The same from the poses (at least one).
Truth tum_truth(const std::vector<io::TumPose>& poses, const std::string& kind);

/// Where every method starts: the first truth pose (GPS: first fix once heading is available,
/// heading from the MRU), else the origin at the first heading reading. Throws io::InputError when
/// the navigation log has no heading at all.
StampedPose initial_pose(const Truth& truth, const NavigationLog& navigation,
                         const std::string& dataset_dir, double heading_sigma_rad);

/// Everything a method reads from a dataset before it runs: the SLAM config, the dataset's files
/// (or its records, for a dataset held in memory) and calibration, its navigation, its truth and
/// the shared start pose.
struct RunInputs {
  SlamConfig config;
  /// Which of the dataset's navigation noise values the config took (slam_config_for_dataset);
  /// "" when none: the commands say it.
  std::string noise_note;
  std::string dataset;  ///< the directory, or the in-memory dataset's name, for messages
  DatasetFiles files;
  std::shared_ptr<const DatasetRecords> records;  ///< set for a dataset held in memory
  Calibration calibration;
  NavigationLog navigation;
  Truth truth;
  StampedPose start;
};

/// Reads and checks them (config_path empty: the default config; either over the dataset's
/// navigation_noise.yaml, slam_config_for_dataset). Throws io::InputError.
RunInputs load_run_inputs(const std::string& dataset_dir, const std::string& config_path,
                          const std::string& calibration_path = "");
/// The same for a dataset held in memory, with the config made for it (slam_config_for_dataset
/// over its records' navigation noise). Throws io::InputError.
RunInputs run_inputs_of(std::shared_ptr<const DatasetRecords> records, SlamConfig config);

}  // namespace msislab::dataset
