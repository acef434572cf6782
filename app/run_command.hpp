// `msislab run DATASET_DIR --method M --out DIR [--config SLAM.yaml]`: runs one method on a dataset
// and writes its result directory (docs/formats.md).
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "app/sonar_readings.hpp"
#include "app/truth.hpp"
#include "eval/evaluation.hpp"
#include "io/results.hpp"
#include "slam/scan_sequence.hpp"

namespace msislab::app {

struct RunOptions {
  std::string dataset_dir;
  std::string method;
  std::string out_dir;
  std::string config_path;  ///< empty: the default SLAM config
};

struct RunOutcome {
  std::vector<StampedPose> trajectory;
  std::optional<RunMetrics> metrics;  ///< present when the dataset has truth (simulation or GPS)
};

/// A method's results on a dataset, computed and not yet written.
struct MethodResult {
  std::string method;
  std::vector<StampedPose> trajectory;
  double depth_m = 0.0;               ///< for the TUM z
  std::optional<RunMetrics> metrics;  ///< present when the dataset has truth
  std::vector<io::NeesSample> nees;   ///< per scan, with pose truth
  std::vector<ErrorSample> errors;    ///< position error at every truth stamp
  double t_first_truth_s = 0.0;
  std::optional<std::vector<PlacedScan>> scans;      ///< with sonar data
  std::optional<std::vector<io::MatchRow>> matches;  ///< SLAM methods
  /// A back end with an online estimate (the pose graph): the smoothed trajectory, written as
  /// trajectory_smoothed.tum and scored as metrics.json's smoothed_* diagnostics.
  std::optional<std::vector<StampedPose>> smoothed_trajectory;
};

/// What several methods on one dataset can share, filled by the first that needs it: the sonar
/// readings (read before any method's clock starts) and the scans placed by dead reckoning (which
/// dead reckoning itself places after its clock; every SLAM method still builds its own scans on
/// its clock).
struct SharedInputs {
  std::optional<SonarInput> sonar;
  std::optional<std::vector<PlacedScan>> dead_reckoning_scans;
};

/// Runs a method on a dataset read already (from a directory or held in memory), sharing with
/// the other methods on it through `shared` when given (the results are the same). Throws
/// io::InputError.
MethodResult run_method(const std::string& method, const RunInputs& in,
                        SharedInputs* shared = nullptr);

/// Writes a result directory (docs/formats.md): trajectory.tum, trajectory_smoothed.tum, scans.csv,
/// map.ply (with write_map), matches.csv, metrics.json and nees.csv, as far as the result has them,
/// each atomically; result files of an earlier run it does not rewrite are removed. dataset_label
/// is recorded in metrics.json as the dataset.
void write_method_result(const std::string& out_dir, const MethodResult& result,
                         const std::string& dataset_label, bool write_map = true);

/// Reads every input first, then runs and writes the result files atomically. Throws
/// io::InputError on bad input (unknown method, missing or malformed files or config).
RunOutcome run(const RunOptions& options);

}  // namespace msislab::app
