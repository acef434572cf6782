// `msislab run DATASET_DIR --method M --out DIR [--config SLAM.yaml]`: runs one method on a dataset
// and writes its result directory (docs/formats.md).
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "slam/evaluation.hpp"

namespace msislab::app {

struct RunOptions {
  std::string dataset_dir;
  std::string method;
  std::string out_dir;
  std::string config_path;  ///< empty: the default SLAM config
};

/// The methods this build can run.
const std::vector<std::string>& available_methods();
/// InputError "OPTION 'm': not available in this build (available: ...)" unless m is one of them.
void check_method(const std::string& method, const std::string& option = "--method");

struct RunOutcome {
  std::vector<StampedPose> trajectory;
  std::optional<RunMetrics> metrics;  ///< present when the dataset has truth (simulation or GPS)
};

/// Reads every input first, then runs and writes the result files atomically. Throws
/// io::InputError on bad input (unknown method, missing or malformed files or config).
RunOutcome run(const RunOptions& options);

}  // namespace msislab::app
