// Putting an estimate from elsewhere onto the truth before scoring it (msislab eval, docs/cli.md):
// a time offset, and the rigid planar motion that best maps its positions onto the truth's.
#pragma once

#include <Eigen/Core>
#include <optional>
#include <vector>

#include "eval/evaluation.hpp"

namespace msislab {

/// T_truth_estimate minimising sum_i |q_i - (R(yaw) p_i + t)|^2 over rigid planar motions (no
/// scale), p_i the estimate's positions and q_i the truth's (Umeyama 1991 without scale; in 2-D
/// the rotation has Horn's closed form). With a_i = p_i - mean(p) and b_i = q_i - mean(q):
///   yaw = atan2(sum_i a_i x b_i, sum_i a_i . b_i),   t = mean(q) - R(yaw) mean(p).
/// Throws std::invalid_argument when the rotation is undetermined: the sizes differ, fewer than 2
/// distinct positions on either side, or sum_i a_i b_i^T without rotation part (every rotation
/// fits equally well).
Pose2 align_se2(const std::vector<Eigen::Vector2d>& p_estimate_m,
                const std::vector<Eigen::Vector2d>& p_truth_m);

/// A truth position with the estimate's position at the same time.
struct MatchedPosition {
  double t_s = 0.0;
  Eigen::Vector2d p_estimate_m = Eigen::Vector2d::Zero();  ///< interpolated
  Eigen::Vector2d p_truth_m = Eigen::Vector2d::Zero();
};

/// The estimate interpolated at every truth stamp inside its time span (the stamps
/// position_errors() scores).
std::vector<MatchedPosition> matched_positions(const std::vector<StampedPose>& estimate,
                                               const std::vector<PositionFix>& truth);

/// The fit of align_se2() and how many matched positions it used.
struct Se2Fit {
  Pose2 T_truth_estimate;
  std::size_t positions = 0;
};

/// align_se2() over the matched positions of the estimate and the truth, all of them, or with
/// window_s only those within window_s seconds of the first. Throws std::invalid_argument as
/// align_se2() does.
Se2Fit fit_se2(const std::vector<StampedPose>& estimate, const std::vector<PositionFix>& truth,
               std::optional<double> window_s = std::nullopt);

/// Every pose moved by T_truth_estimate: T (+) x with the covariance J2+ P J2+^T, J2+ = diag(R, 1)
/// (T is exact).
std::vector<StampedPose> transform_poses(const Pose2& T_truth_estimate,
                                         const std::vector<StampedPose>& poses);

/// Every stamp moved to t_s + t_offset_s.
std::vector<StampedPose> shift_times(std::vector<StampedPose> poses, double t_offset_s);

}  // namespace msislab
