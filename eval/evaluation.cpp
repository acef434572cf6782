#include "eval/evaluation.hpp"

#include <limits>

#include <algorithm>
#include <cassert>
#include <cmath>

#include <Eigen/Cholesky>

#include "eval/alignment.hpp"
#include "stats/sample_statistics.hpp"

namespace msislab {

Pose2 interpolate_pose(const std::vector<StampedPose>& trajectory, double t_s) {
  assert(!trajectory.empty());
  auto after = std::lower_bound(trajectory.begin(), trajectory.end(), t_s,
                                [](const StampedPose& p, double t) { return p.t_s < t; });
  if (after == trajectory.begin()) return after->pose.mean;
  if (after == trajectory.end()) return trajectory.back().pose.mean;
  const Pose2& a = std::prev(after)->pose.mean;
  const Pose2& b = after->pose.mean;
  const double span_s = after->t_s - std::prev(after)->t_s;
  const double w = span_s > 0.0 ? (t_s - std::prev(after)->t_s) / span_s : 1.0;
  const Eigen::Vector3d d = pose_difference(b, a);
  return Pose2(a.vector() + w * d);
}

Eigen::Vector2d interpolate_position(const std::vector<PositionFix>& track, double t_s) {
  assert(!track.empty());
  auto after = std::lower_bound(track.begin(), track.end(), t_s,
                                [](const PositionFix& p, double t) { return p.t_s < t; });
  if (after == track.begin()) return after->p_world_m;
  if (after == track.end()) return track.back().p_world_m;
  const PositionFix& a = *std::prev(after);
  const double w = (t_s - a.t_s) / (after->t_s - a.t_s);
  return a.p_world_m + w * (after->p_world_m - a.p_world_m);
}

std::vector<ErrorSample> position_errors(const std::vector<StampedPose>& estimate,
                                         const std::vector<PositionFix>& truth) {
  std::vector<ErrorSample> errors;
  for (const MatchedPosition& m : matched_positions(estimate, truth)) {
    errors.push_back({m.t_s, (m.p_estimate_m - m.p_truth_m).norm()});
  }
  return errors;
}

namespace {
/// The truth position at t_s; nullopt outside the fixes or between fixes more than max_fix_gap_s
/// apart.
std::optional<Eigen::Vector2d> position_at(const std::vector<PositionFix>& truth, double t_s,
                                           double max_fix_gap_s) {
  auto after = std::lower_bound(truth.begin(), truth.end(), t_s,
                                [](const PositionFix& f, double t) { return f.t_s < t; });
  if (after == truth.end()) return std::nullopt;
  if (after->t_s != t_s &&
      (after == truth.begin() || after->t_s - std::prev(after)->t_s > max_fix_gap_s)) {
    return std::nullopt;
  }
  return interpolate_position(truth, t_s);
}
}  // namespace

std::optional<double> match_translation_scale(const std::vector<MatchTranslation>& matches,
                                              const std::vector<PositionFix>& truth,
                                              double min_displacement_m, double max_fix_gap_s) {
  double along_m = 0.0, true_m = 0.0;
  for (const MatchTranslation& m : matches) {
    const std::optional<Eigen::Vector2d> p_reference_world_m =
        position_at(truth, m.t_reference_s, max_fix_gap_s);
    const std::optional<Eigen::Vector2d> p_world_m = position_at(truth, m.t_s, max_fix_gap_s);
    if (!p_reference_world_m || !p_world_m) continue;
    const Eigen::Vector2d d_world_m = *p_world_m - *p_reference_world_m;
    const double length_m = d_world_m.norm();
    if (!(length_m >= min_displacement_m)) continue;
    // d in the reference scan's frame: R(yaw)^T d.
    const double c = std::cos(m.yaw_reference_rad), s = std::sin(m.yaw_reference_rad);
    const Eigen::Vector2d d_reference_m(c * d_world_m.x() + s * d_world_m.y(),
                                        -s * d_world_m.x() + c * d_world_m.y());
    along_m += m.translation_reference_m.dot(d_reference_m) / length_m;
    true_m += length_m;
  }
  if (true_m <= 0.0) return std::nullopt;
  return along_m / true_m;
}

std::optional<ErrorStats> error_stats(const std::vector<ErrorSample>& errors) {
  if (errors.empty()) return std::nullopt;
  ErrorStats stats;
  stats.count = errors.size();
  std::vector<double> values;
  values.reserve(errors.size());
  double sum = 0.0, sum_sq = 0.0;
  for (const ErrorSample& e : errors) {
    values.push_back(e.error_m);
    sum += e.error_m;
    sum_sq += e.error_m * e.error_m;
  }
  const double n = static_cast<double>(values.size());
  stats.mean_m = sum / n;
  stats.rmse_m = std::sqrt(sum_sq / n);
  stats.max_m = *std::max_element(values.begin(), values.end());
  stats.final_m = errors.back().error_m;
  stats.median_m = median(std::move(values));
  return stats;
}

std::optional<double> segment_mean_error(const std::vector<ErrorSample>& errors, double t0_s,
                                         const TimeSegment& segment) {
  double sum = 0.0;
  std::size_t count = 0;
  for (const ErrorSample& e : errors) {
    const double t_rel = e.t_s - t0_s;
    if (t_rel >= segment.begin_s && t_rel < segment.end_s) {
      sum += e.error_m;
      ++count;
    }
  }
  if (count == 0) return std::nullopt;
  return sum / static_cast<double>(count);
}

std::vector<double> pose_nees(const std::vector<StampedPose>& estimate,
                              const std::vector<StampedPose>& truth) {
  assert(!truth.empty());
  std::vector<double> nees;
  nees.reserve(estimate.size());
  for (const StampedPose& p : estimate) {
    const Eigen::Vector3d e = pose_difference(p.pose.mean, interpolate_pose(truth, p.t_s));
    const Eigen::LDLT<Eigen::Matrix3d, Eigen::Upper> P(p.pose.cov);
    nees.push_back(e.dot(P.solve(e)));
  }
  return nees;
}

double observed_nees(const GaussianPose2& z, const Eigen::MatrixXd& observed, const Pose2& truth) {
  const Eigen::VectorXd e = observed * pose_difference(z.mean, truth);
  const Eigen::MatrixXd R = observed * z.cov * observed.transpose();
  return e.dot(R.ldlt().solve(e));
}

std::optional<double> mean_of(const std::vector<double>& values) {
  if (values.empty()) return std::nullopt;
  return mean(values);
}

}  // namespace msislab
