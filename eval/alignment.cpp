#include "eval/alignment.hpp"

#include <cmath>
#include <stdexcept>
#include <string>

namespace msislab {

namespace {

/// Whether the points hold at least two distinct ones.
bool has_two_distinct(const std::vector<Eigen::Vector2d>& points) {
  for (const Eigen::Vector2d& p : points) {
    if (p != points.front()) return true;
  }
  return false;
}

Eigen::Vector2d centroid(const std::vector<Eigen::Vector2d>& points) {
  Eigen::Vector2d sum = Eigen::Vector2d::Zero();
  for (const Eigen::Vector2d& p : points) sum += p;
  return sum / static_cast<double>(points.size());
}

}  // namespace

Pose2 align_se2(const std::vector<Eigen::Vector2d>& p_estimate_m,
                const std::vector<Eigen::Vector2d>& p_truth_m) {
  if (p_estimate_m.size() != p_truth_m.size()) {
    throw std::invalid_argument("SE(2) alignment: " + std::to_string(p_estimate_m.size()) +
                                " estimate positions against " + std::to_string(p_truth_m.size()) +
                                " truth positions");
  }
  if (!has_two_distinct(p_estimate_m) || !has_two_distinct(p_truth_m)) {
    throw std::invalid_argument(
        "SE(2) alignment needs at least 2 distinct positions in the estimate and in the truth "
        "(matched positions: " +
        std::to_string(p_estimate_m.size()) + ")");
  }
  const Eigen::Vector2d mean_estimate = centroid(p_estimate_m);
  const Eigen::Vector2d mean_truth = centroid(p_truth_m);
  double dot = 0.0, cross = 0.0, norm_estimate = 0.0, norm_truth = 0.0;
  for (std::size_t i = 0; i < p_estimate_m.size(); ++i) {
    const Eigen::Vector2d a = p_estimate_m[i] - mean_estimate;
    const Eigen::Vector2d b = p_truth_m[i] - mean_truth;
    dot += a.dot(b);
    cross += a.x() * b.y() - a.y() * b.x();
    norm_estimate += a.squaredNorm();
    norm_truth += b.squaredNorm();
  }
  // |sum a_i conj-times b_i| against the Cauchy-Schwarz bound: the cost is the same for every
  // rotation when it vanishes.
  if (!(std::hypot(dot, cross) > 1e-12 * std::sqrt(norm_estimate * norm_truth))) {
    throw std::invalid_argument(
        "SE(2) alignment: the rotation is undetermined (the estimate's and the truth's positions "
        "are uncorrelated)");
  }
  const double yaw_rad = std::atan2(cross, dot);
  const Pose2 rotation(0.0, 0.0, yaw_rad);
  const Eigen::Vector2d t_m = mean_truth - rotation.rotation() * mean_estimate;
  return Pose2(t_m.x(), t_m.y(), yaw_rad);
}

std::vector<MatchedPosition> matched_positions(const std::vector<StampedPose>& estimate,
                                               const std::vector<PositionFix>& truth) {
  std::vector<MatchedPosition> matched;
  if (estimate.empty()) return matched;
  const double t_begin = estimate.front().t_s, t_end = estimate.back().t_s;
  for (const PositionFix& fix : truth) {
    if (fix.t_s < t_begin || fix.t_s > t_end) continue;
    matched.push_back({fix.t_s, interpolate_pose(estimate, fix.t_s).translation(), fix.p_world_m});
  }
  return matched;
}

Se2Fit fit_se2(const std::vector<StampedPose>& estimate, const std::vector<PositionFix>& truth,
               std::optional<double> window_s) {
  const std::vector<MatchedPosition> matched = matched_positions(estimate, truth);
  std::vector<Eigen::Vector2d> p_estimate_m, p_truth_m;
  for (const MatchedPosition& m : matched) {
    if (window_s && m.t_s - matched.front().t_s > *window_s) break;
    p_estimate_m.push_back(m.p_estimate_m);
    p_truth_m.push_back(m.p_truth_m);
  }
  return {align_se2(p_estimate_m, p_truth_m), p_estimate_m.size()};
}

std::vector<StampedPose> transform_poses(const Pose2& T_truth_estimate,
                                         const std::vector<StampedPose>& poses) {
  const GaussianPose2 exact{T_truth_estimate, Eigen::Matrix3d::Zero()};
  std::vector<StampedPose> moved;
  moved.reserve(poses.size());
  for (const StampedPose& p : poses) moved.push_back({p.t_s, compose(exact, p.pose)});
  return moved;
}

std::vector<StampedPose> shift_times(std::vector<StampedPose> poses, double t_offset_s) {
  for (StampedPose& p : poses) p.t_s += t_offset_s;
  return poses;
}

}  // namespace msislab
