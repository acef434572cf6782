// `msislab run DATASET_DIR --method M --out DIR [--config SLAM.yaml]`: runs one method on a dataset
// and writes its result directory (docs/formats.md).
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "app/run_method.hpp"
#include "dataset/sonar_readings.hpp"
#include "dataset/truth.hpp"
#include "eval/evaluation.hpp"
#include "results/results.hpp"
#include "slam/scan_sequence.hpp"

namespace msislab::app {

struct RunOptions {
  std::string dataset_dir;
  std::string method;
  std::string out_dir;
  std::string config_path;         ///< empty: the default SLAM config
  bool force = false;              ///< replace a folder msislab did not write
  std::string methods_file{};      ///< external methods (docs/formats.md); empty: none
  std::string calibration_path{};  ///< a calibration.yaml in place of the dataset's; empty: its own
};

struct RunOutcome {
  std::vector<StampedPose> trajectory;
  std::optional<RunMetrics> metrics;  ///< present when the dataset has truth (simulation or GPS)
};

/// Checks the output path and reads every input first, then runs and puts the result directory in
/// place whole (io::StagedFolder). Throws io::InputError on bad input (unknown method, missing or
/// malformed files or config, an output path msislab may not write), ExternalMethodError when an
/// external method gave no result (nothing is written then).
RunOutcome run(const RunOptions& options);

}  // namespace msislab::app
