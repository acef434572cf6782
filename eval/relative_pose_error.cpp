#include "eval/relative_pose_error.hpp"

#include <algorithm>
#include <cassert>
#include <cmath>

#include "eval/evaluation.hpp"
#include "stats/sample_statistics.hpp"

namespace msislab {

namespace {

SampleSummary summary_of(const std::vector<double>& values) {
  SampleSummary s;
  double sum = 0.0, sum_sq = 0.0;
  for (const double v : values) {
    sum += v;
    sum_sq += v * v;
  }
  const double n = static_cast<double>(values.size());
  s.mean = sum / n;
  s.rmse = std::sqrt(sum_sq / n);
  s.median = quantile(values, 0.5);
  s.max = *std::max_element(values.begin(), values.end());
  return s;
}

}  // namespace

RelativePoseError relative_pose_error(const std::vector<StampedPose>& estimate,
                                      const std::vector<StampedPose>& truth, double delta_m) {
  assert(!estimate.empty() && delta_m > 0.0);
  RelativePoseError rpe;
  rpe.delta_m = delta_m;
  std::vector<Pose2> true_poses, estimated_poses;
  std::vector<double> path_m;  // truth path length from the first sample
  for (const StampedPose& t : truth) {
    if (t.t_s < estimate.front().t_s || t.t_s > estimate.back().t_s) continue;
    path_m.push_back(
        true_poses.empty()
            ? 0.0
            : path_m.back() + (t.pose.mean.translation() - true_poses.back().translation()).norm());
    true_poses.push_back(t.pose.mean);
    estimated_poses.push_back(interpolate_pose(estimate, t.t_s));
  }
  std::vector<double> translation_m, rotation_deg;
  std::size_t j = 0;
  for (std::size_t i = 0; i < true_poses.size(); ++i) {
    j = std::max(j, i + 1);
    while (j < true_poses.size() && path_m[j] - path_m[i] < delta_m) ++j;
    if (j == true_poses.size()) break;
    // E_ij = (T_est_i^-1 T_est_j)^-1 (T_true_i^-1 T_true_j)
    const Pose2 E = estimated_poses[i]
                        .between(estimated_poses[j])
                        .between(true_poses[i].between(true_poses[j]));
    translation_m.push_back(E.translation().norm());
    rotation_deg.push_back(std::abs(E.yaw()) * 180.0 / M_PI);
  }
  rpe.pairs = translation_m.size();
  if (rpe.pairs > 0) {
    rpe.translation_m = summary_of(translation_m);
    rpe.rotation_deg = summary_of(rotation_deg);
  }
  return rpe;
}

}  // namespace msislab
