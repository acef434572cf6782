// `msislab eval RESULT_DIR [--truth FILE] [--config SLAM.yaml] [--name NAME] [--t-offset S]
// [--align none|se2|se2:N] [--rpe-delta-m D]`: (re)scores a result directory, or a trajectory from
// elsewhere, against truth (docs/cli.md), with the scoring of app/method_result.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "dataset/truth.hpp"
#include "eval/evaluation.hpp"
#include "results/results.hpp"

namespace msislab::app {

struct EvalOptions {
  std::string result_dir;
  std::string truth_path;   ///< empty: the truth of the dataset recorded in metrics.json
  std::string config_path;  ///< empty: the segment windows recorded in metrics.json
  std::string name;         ///< the method recorded; empty: the recorded one, else "unknown"
  double t_offset_s = 0.0;  ///< added to the estimate's stamps: t_truth = t_estimate + t_offset_s
  std::string align = "none";  ///< "none", "se2" or "se2:N" (parse_align_option)
  double rpe_delta_m = 10.0;   ///< truth path length between the poses of an RPE pair
};

/// --align read: whether to fit SE(2), and over the first window_s seconds of the overlap only.
struct AlignOption {
  bool se2 = false;
  std::optional<double> window_s;
};
/// Reads "none", "se2" or "se2:N" (N seconds, finite, > 0). Throws io::InputError naming --align.
AlignOption parse_align_option(const std::string& text);

struct EvalOutcome {
  RunMetrics metrics;
  std::size_t nees_rows = 0;  ///< rows written to nees.csv
};

/// Reads the result directory and the truth, shifts and aligns the estimate as the options say,
/// re-scores the trajectory and the scan poses, and rewrites metrics.json (keeping the run's own
/// figures, adding the alignment and the RPE) and nees.csv. Throws io::InputError.
EvalOutcome evaluate(const EvalOptions& options);

}  // namespace msislab::app
