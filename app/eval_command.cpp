#include "app/eval_command.hpp"

#include <CLI/CLI.hpp>
#include <filesystem>
#include <iomanip>
#include <iostream>
#include <limits>
#include <memory>
#include <optional>

#include "app/cli.hpp"
#include "io/atomic_file.hpp"
#include "io/config_yaml.hpp"
#include "io/dataset.hpp"
#include "io/input_error.hpp"
#include "io/tum.hpp"

namespace msislab::app {

namespace fs = std::filesystem;

RunMetrics score_trajectory(const Truth& truth, const std::vector<StampedPose>& trajectory,
                            const std::vector<TimeSegment>& segments, const std::string& source) {
  return score_errors(truth, position_errors(trajectory, truth.positions), segments, source);
}

RunMetrics score_errors(const Truth& truth, const std::vector<ErrorSample>& errors,
                        const std::vector<TimeSegment>& segments, const std::string& source) {
  const std::optional<ErrorStats> stats = error_stats(errors);
  if (!stats) io::fail_file(source, "no " + truth.kind + " truth inside the estimated span");
  RunMetrics metrics;
  metrics.truth = truth.kind;
  metrics.errors = *stats;
  metrics.segment_windows = segments;
  for (const TimeSegment& segment : segments) {
    metrics.segments.emplace_back(segment.name,
                                  segment_mean_error(errors, truth.positions.front().t_s, segment));
  }
  return metrics;
}

std::vector<io::NeesSample> scan_nees(const std::vector<StampedPose>& scan_poses,
                                      const Truth& truth) {
  std::vector<io::NeesSample> samples;
  if (truth.poses.empty()) return samples;
  const std::vector<double> nees = pose_nees(scan_poses, truth.poses);
  for (std::size_t i = 0; i < nees.size(); ++i) samples.push_back({scan_poses[i].t_s, nees[i]});
  return samples;
}

std::optional<double> average_nees(const std::vector<io::NeesSample>& nees) {
  std::vector<double> values;
  values.reserve(nees.size());
  for (const io::NeesSample& s : nees) values.push_back(s.nees);
  return mean_of(values);
}

void write_scores(const std::string& out_dir, const RunMetrics& metrics,
                  const std::vector<io::NeesSample>& nees, const std::string& dataset_dir,
                  const std::string& truth_file) {
  const fs::path out(out_dir);
  if (nees.empty()) {
    std::error_code ec;
    fs::remove(out / "nees.csv", ec);
  } else {
    io::write_nees_csv((out / "nees.csv").string(), nees);
  }
  io::write_metrics_json((out / "metrics.json").string(), metrics, dataset_dir, truth_file);
}

namespace {

/// The run's own record. A result written without truth has none: then only --truth can score it,
/// and the run's figures are unknown.
io::StoredMetrics read_run_record(const EvalOptions& options, const fs::path& dir) {
  const std::string path = (dir / "metrics.json").string();
  if (fs::exists(path)) return io::read_metrics_json(path);
  if (options.truth_path.empty()) {
    io::fail_file(path, "missing (a result written without truth needs --truth FILE)");
  }
  io::StoredMetrics stored;
  stored.metrics.method = "unknown";
  stored.metrics.runtime_s = std::numeric_limits<double>::quiet_NaN();
  return stored;
}

Truth dataset_truth(const io::StoredMetrics& stored, const std::string& metrics_path) {
  if (stored.dataset_dir.empty() || !fs::is_directory(stored.dataset_dir)) {
    io::fail_file(metrics_path, "key 'dataset': the dataset '" + stored.dataset_dir +
                                    "' is not there any more; give --truth FILE");
  }
  const io::DatasetFiles files = io::find_dataset_files(stored.dataset_dir);
  Truth truth = load_truth(files, io::load_calibration(files));
  if (truth.kind.empty()) {
    io::fail_file(stored.dataset_dir,
                  "the dataset has no truth (truth/trajectory.tum or "
                  "*_DGPS.log); give --truth FILE");
  }
  return truth;
}

}  // namespace

EvalOutcome evaluate(const EvalOptions& options) {
  const fs::path dir(options.result_dir);
  if (!fs::is_directory(dir)) io::fail_file(options.result_dir, "no such result directory");
  const bool has_record = fs::exists(dir / "metrics.json");
  const io::StoredMetrics stored = read_run_record(options, dir);
  const std::vector<TimeSegment> segments =
      options.config_path.empty() ? stored.metrics.segment_windows
                                  : io::read_slam_config(options.config_path).segments;
  std::vector<StampedPose> trajectory;
  for (const io::TumPose& p : io::read_tum((dir / "trajectory.tum").string())) {
    trajectory.push_back({p.t_s, {Pose2(p.x_m, p.y_m, p.yaw_rad)}});
  }
  const fs::path scans_path = dir / "scans.csv";
  std::optional<std::vector<StampedPose>> scans;
  if (fs::exists(scans_path)) scans = io::read_scans_csv(scans_path.string());
  const Truth truth = options.truth_path.empty()
                          ? dataset_truth(stored, (dir / "metrics.json").string())
                          : read_tum_truth(options.truth_path, "tum");

  EvalOutcome outcome;
  RunMetrics& metrics = outcome.metrics;
  metrics = score_trajectory(truth, trajectory, segments,
                             options.truth_path.empty() ? stored.dataset_dir : options.truth_path);
  metrics.method = stored.metrics.method;
  metrics.scans = stored.metrics.scans;
  if (!has_record && scans) metrics.scans = static_cast<int>(scans->size());
  metrics.matches_accepted = stored.metrics.matches_accepted;
  metrics.runtime_s = stored.metrics.runtime_s;
  metrics.diagnostics = stored.metrics.diagnostics;
  std::vector<io::NeesSample> nees;
  if (scans) nees = scan_nees(*scans, truth);
  metrics.anees = average_nees(nees);
  outcome.nees_rows = nees.size();
  write_scores(options.result_dir, metrics, nees, stored.dataset_dir,
               options.truth_path.empty() ? "" : io::absolute_path(options.truth_path));
  return outcome;
}

void add_eval_command(CLI::App& app, CommandLine&) {
  auto options = std::make_shared<EvalOptions>();
  CLI::App* eval = app.add_subcommand(
      "eval",
      "Re-score a result directory of `msislab run` against truth; rewrites metrics.json and "
      "nees.csv");
  eval->add_option("RESULT_DIR", options->result_dir,
                   "Result directory (trajectory.tum, metrics.json, scans.csv)")
      ->required();
  eval->add_option("--truth,-t", options->truth_path,
                   "TUM truth file (default: the truth of the dataset recorded in metrics.json)");
  eval->add_option("--config,-c", options->config_path,
                   "SLAM config YAML whose segments replace the recorded segment windows");
  eval->callback([options] {
    const EvalOutcome outcome = evaluate(*options);
    std::cout << std::fixed << std::setprecision(3) << "wrote " << options->result_dir
              << "/metrics.json: mean error " << outcome.metrics.errors.mean_m << " m against "
              << outcome.metrics.truth;
    if (outcome.metrics.anees) {
      std::cout << ", ANEES " << *outcome.metrics.anees << " over " << outcome.nees_rows
                << " scans (nees.csv)";
    }
    std::cout << std::endl;
  });
}

}  // namespace msislab::app
