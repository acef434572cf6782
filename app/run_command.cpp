#include "app/run_command.hpp"

#include <algorithm>
#include <chrono>
#include <filesystem>

#include "app/truth.hpp"
#include "io/atomic_file.hpp"
#include "io/dataset.hpp"
#include "io/input_error.hpp"
#include "io/results.hpp"
#include "slam/dead_reckoning.hpp"

namespace msislab::app {

namespace fs = std::filesystem;

const std::vector<std::string>& available_methods() {
  static const std::vector<std::string> methods = {"deadreckoning", "integration"};
  return methods;
}

namespace {
void check_method(const std::string& method) {
  const auto& methods = available_methods();
  if (std::find(methods.begin(), methods.end(), method) != methods.end()) return;
  std::string list;
  for (const std::string& m : methods) list += (list.empty() ? "" : ", ") + m;
  throw io::InputError("--method '" + method +
                       "': not available in this build (available: " + list + ")");
}

RunMetrics score(const Truth& truth, const std::vector<StampedPose>& trajectory,
                 const SlamConfig& config, const std::string& dataset_dir) {
  const std::vector<ErrorSample> errors = position_errors(trajectory, truth.positions);
  const std::optional<ErrorStats> stats = error_stats(errors);
  if (!stats) io::fail_file(dataset_dir, "no " + truth.kind + " truth inside the estimated span");
  RunMetrics metrics;
  metrics.truth = truth.kind;
  metrics.errors = *stats;
  for (const TimeSegment& segment : config.segments) {
    metrics.segments.emplace_back(segment.name,
                                  segment_mean_error(errors, truth.positions.front().t_s, segment));
  }
  return metrics;
}

/// Creates the result directory and removes result files a previous run left that this run
/// will not rewrite, so the directory never mixes two runs.
void prepare_out_dir(const std::string& out_dir, bool writes_metrics) {
  io::create_output_dir(out_dir);
  std::error_code ec;
  for (const char* stale : {"scans.csv", "map.ply"}) fs::remove(fs::path(out_dir) / stale, ec);
  if (!writes_metrics) fs::remove(fs::path(out_dir) / "metrics.json", ec);
}
}  // namespace

RunOutcome run(const RunOptions& options) {
  check_method(options.method);
  const RunInputs in = load_run_inputs(options.dataset_dir, options.config_path);
  const SlamConfig& config = in.config;
  const Calibration& calibration = in.calibration;
  const NavigationLog& navigation = in.navigation;
  const Truth& truth = in.truth;
  const StampedPose& start = in.start;

  const auto t_begin = std::chrono::steady_clock::now();
  const Eigen::Vector2d p_vehicle_dvl_m(calibration.dvl.x_m, calibration.dvl.y_m);
  DeadReckoningResult dr;
  if (options.method == "integration") {
    dr.trajectory = integrate_velocities(navigation, start);
  } else {
    dr = run_dead_reckoning(navigation, config.dead_reckoning, p_vehicle_dvl_m, start);
  }
  const double runtime_s =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - t_begin).count();
  if (dr.trajectory.size() < 2) {
    io::fail_file(options.dataset_dir, "no navigation data after the start time");
  }

  RunOutcome outcome;
  outcome.trajectory = dr.trajectory;
  if (!truth.kind.empty()) {
    outcome.metrics = score(truth, dr.trajectory, config, options.dataset_dir);
    outcome.metrics->method = options.method;
    outcome.metrics->runtime_s = runtime_s;
    if (options.method == "deadreckoning") {
      outcome.metrics->diagnostics = {
          {"dvl_used", dr.dvl_used},
          {"dvl_rejected", dr.dvl_rejected},
          {"dvl_without_bottom_lock", navigation.dvl_rows_without_bottom_lock},
          {"dvl_mean_nis", dr.dvl_mean_nis},
          {"heading_used", dr.heading_used},
          {"heading_mean_nis", dr.heading_mean_nis}};
    }
  }

  prepare_out_dir(options.out_dir, outcome.metrics.has_value());
  const fs::path out(options.out_dir);
  io::write_trajectory_tum((out / "trajectory.tum").string(), dr.trajectory, truth.depth_m);
  if (outcome.metrics) {
    io::write_metrics_json((out / "metrics.json").string(), *outcome.metrics,
                           fs::absolute(options.dataset_dir).lexically_normal().string());
  }
  return outcome;
}

}  // namespace msislab::app
