#include "app/method_result.hpp"

#include <filesystem>

#include "io/atomic_file.hpp"
#include "io/input_error.hpp"
#include "settings/config_yaml.hpp"

namespace msislab::app {

namespace fs = std::filesystem;

RunMetrics score_trajectory(const dataset::Truth& truth, const std::vector<StampedPose>& trajectory,
                            const std::vector<TimeSegment>& segments, const std::string& source) {
  return score_errors(truth, position_errors(trajectory, truth.positions), segments, source);
}

RunMetrics score_errors(const dataset::Truth& truth, const std::vector<ErrorSample>& errors,
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

std::vector<results::NeesSample> scan_nees(const std::vector<StampedPose>& scan_poses,
                                           const dataset::Truth& truth) {
  std::vector<results::NeesSample> samples;
  if (truth.poses.empty()) return samples;
  const std::vector<double> nees = pose_nees(scan_poses, truth.poses);
  for (std::size_t i = 0; i < nees.size(); ++i) samples.push_back({scan_poses[i].t_s, nees[i]});
  return samples;
}

std::optional<double> average_nees(const std::vector<results::NeesSample>& nees) {
  std::vector<double> values;
  values.reserve(nees.size());
  for (const results::NeesSample& s : nees) values.push_back(s.nees);
  return mean_of(values);
}

void write_scores(const std::string& out_dir, const RunMetrics& metrics,
                  const std::vector<results::NeesSample>& nees, const std::string& dataset_dir,
                  const std::string& truth_file) {
  const fs::path out(out_dir);
  if (nees.empty()) {
    std::error_code ec;
    fs::remove(out / "nees.csv", ec);
  } else {
    results::write_nees_csv((out / "nees.csv").string(), nees);
  }
  results::write_metrics_json((out / "metrics.json").string(), metrics, dataset_dir, truth_file);
}

void write_method_result(const std::string& out_dir, const MethodResult& result,
                         const std::string& dataset_label, bool write_map) {
  io::create_output_dir(out_dir);
  const fs::path out(out_dir);
  results::write_trajectory_tum((out / "trajectory.tum").string(), result.trajectory,
                                result.depth_m);
  if (result.smoothed_trajectory) {
    results::write_trajectory_tum((out / "trajectory_smoothed.tum").string(),
                                  *result.smoothed_trajectory, result.depth_m);
  }
  if (result.scans) {
    results::write_scans_csv((out / "scans.csv").string(), *result.scans);
    if (write_map)
      results::write_points_ply((out / "map.ply").string(), world_points(*result.scans));
  }
  if (result.matches) results::write_matches_csv((out / "matches.csv").string(), *result.matches);
  if (!result.calibration_history.empty()) {
    results::write_calibration_csv((out / "calibration.csv").string(), result.calibration_history);
  }
  if (result.estimated_calibration) {
    settings::write_calibration((out / "calibration.yaml").string(), *result.estimated_calibration);
  }
  if (result.metrics) write_scores(out_dir, *result.metrics, result.nees, dataset_label);
}

}  // namespace msislab::app
