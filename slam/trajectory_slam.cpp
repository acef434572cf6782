#include "slam/trajectory_slam.hpp"

#include <Eigen/Cholesky>
#include <Eigen/LU>
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>

namespace msislab {

namespace {

/// A motion whose covariance says "unknown": 100 m and pi rad standard deviation.
GaussianPose2 unknown_motion() {
  return {Pose2(), Eigen::Vector3d(1e4, 1e4, M_PI * M_PI).asDiagonal()};
}

std::vector<ScanPoint> finite_points(const std::vector<ScanPoint>& points) {
  std::vector<ScanPoint> finite;
  finite.reserve(points.size());
  for (const ScanPoint& p : points) {
    if (p.p_m.allFinite() && p.cov.allFinite()) finite.push_back(p);
  }
  return finite;
}

/// The innovation gate for d observed directions at the tail probability of the configured
/// 3-DOF gate (chi-square, 99 % by default): 3 DOF keeps the configured value.
double gate_for_dimensions(double gate_3dof, Eigen::Index d) {
  if (d == 3) return gate_3dof;
  return chi2_quantile(1.0 - chi2_survival(gate_3dof, 3), static_cast<int>(d));
}

}  // namespace

void MatchRejectionCounts::count(const ValidatedMatch& match) {
  if (match.rejection == MatchRejection::kNone) {
    direction_dropped += match.direction_dropped;
  } else {
    ++rejected[static_cast<std::size_t>(match.rejection)];
  }
}

TrajectorySlam::TrajectorySlam(const TrajectorySlamConfig& config, const GaussianPose2& start_world)
    : config_(config), start_world_(start_world) {}

void TrajectorySlam::predict(const GaussianPose2& motion) {
  const Eigen::Index n = static_cast<Eigen::Index>(3 * elements_.size());
  elements_.push_back(motion.mean);
  P_.conservativeResize(n + 3, n + 3);
  P_.rightCols<3>().setZero();
  P_.bottomRows<3>().setZero();
  P_.bottomRightCorner<3, 3>() = motion.cov;
}

Eigen::Matrix3d TrajectorySlam::propagate(std::size_t first, const Eigen::MatrixXd& J) const {
  const Eigen::Index f = static_cast<Eigen::Index>(3 * first);
  return J * P_.block(f, f, J.cols(), J.cols()) * J.transpose();
}

SlamStepStats TrajectorySlam::add_scan(const Scan& scan) {
  SlamStepStats stats;
  const bool motion_ok = scan.motion.mean.vector().allFinite() && scan.motion.cov.allFinite();
  predict(motion_ok ? scan.motion : unknown_motion());
  group_start_.push_back(elements_.size() - 1);
  points_.push_back(finite_points(scan.points));
  ++totals_.scans;

  const std::size_t k = elements_.size() - 1;
  if (config_.compass_updates && std::isfinite(scan.compass_yaw_world_rad) &&
      scan.compass_sigma_rad > 0.0) {
    stats.compass_accepted = update_compass(k, scan.compass_yaw_world_rad, scan.compass_sigma_rad,
                                            stats.window_elements);
    totals_.compass_accepted += stats.compass_accepted;
  }
  if (!motion_ok || static_cast<int>(points_[k].size()) < config_.matching.min_inliers) {
    stats.skipped = true;
    ++totals_.skipped;
    finish_step();
    return stats;
  }

  // Associate (paper Eq. 3-4): past scans within gamma, nearest first.
  const std::vector<double> distances_m = distances_to_newest();
  std::vector<std::pair<double, std::size_t>> candidates;
  for (std::size_t j = 0; j + static_cast<std::size_t>(config_.min_scan_gap) <= k; ++j) {
    if (distances_m[j] < config_.association_distance_m &&
        static_cast<int>(points_[j].size()) >= config_.matching.min_inliers) {
      candidates.emplace_back(distances_m[j], j);
    }
  }
  std::sort(candidates.begin(), candidates.end());
  if (static_cast<int>(candidates.size()) > config_.max_matches_per_scan) {
    candidates.resize(static_cast<std::size_t>(config_.max_matches_per_scan));
  }
  stats.candidates = static_cast<int>(candidates.size());

  // Observe and update, one match at a time.
  for (const auto& [distance_m, j] : candidates) {
    Eigen::MatrixXd H;
    GaussianPose2 guess;
    guess.mean = relative_pose(j, k, &H);
    guess.cov = propagate(j + 1, H);
    ValidatedMatch match =
        match_and_validate(points_[j], points_[k], guess, config_.matching, config_.validation);
    if (match.match.valid) ++stats.matched;
    if (match.rejection == MatchRejection::kNone) {
      if (update_match(j, k, match.match.estimate, match.observed, stats.window_elements)) {
        ++stats.accepted;
      } else {
        match.rejection = MatchRejection::kInnovation;
      }
    }
    stats.rejections.count(match);
    totals_.rejections.count(match);
  }
  totals_.candidates += stats.candidates;
  totals_.matched += stats.matched;
  totals_.accepted += stats.accepted;
  finish_step();
  return stats;
}

template <class Residual>
bool TrajectorySlam::update(std::size_t first_involved, std::size_t b, const Residual& residual,
                            const Eigen::MatrixXd& R, double gate_chi2, int& window_elements) {
  // The window: from the start of the group holding the first involved element to b (the newest
  // element), which takes in every element correlated with the ones h depends on.
  const std::size_t first = config_.update_whole_state ? 0 : group_start_[first_involved];
  const std::size_t count = b + 1 - first;
  const Eigen::Index m = static_cast<Eigen::Index>(3 * count);
  const Eigen::Index f = static_cast<Eigen::Index>(3 * first);
  const Eigen::Index h_col = static_cast<Eigen::Index>(3 * (first_involved - first));
  const Eigen::Index d = R.rows();
  const auto P_window = P_.block(f, f, m, m);

  // Iterated EKF (paper Eq. 9-10): X_{i+1} = X^ + K_i (z - h(X_i) - H_i (X^ - X_i)),
  // K_i = P H_i^T (H_i P H_i^T + R)^-1; then P = (I - K H) P at the last linearisation.
  const std::vector<Pose2> prior(elements_.begin() + static_cast<long>(first),
                                 elements_.begin() + static_cast<long>(b) + 1);
  Eigen::VectorXd x_prior(m);
  for (std::size_t j = 0; j < count; ++j) {
    x_prior.segment<3>(static_cast<Eigen::Index>(3 * j)) = prior[j].vector();
  }
  Eigen::MatrixXd H = Eigen::MatrixXd::Zero(d, m), H_involved, K, PHt;
  for (int iteration = 0; iteration < std::max(1, config_.iekf_iterations); ++iteration) {
    const Eigen::VectorXd z_minus_h = residual(&H_involved);
    H.middleCols(h_col, H_involved.cols()) = H_involved;
    Eigen::VectorXd dx(m);  // X^ - X_i, angles wrapped
    for (std::size_t j = 0; j < count; ++j) {
      dx.segment<3>(static_cast<Eigen::Index>(3 * j)) =
          pose_difference(prior[j], elements_[first + j]);
    }
    PHt.noalias() = P_window * H.transpose();
    const Eigen::MatrixXd S = H * PHt + R;
    const Eigen::VectorXd innovation = z_minus_h - H * dx;
    if (iteration == 0 && innovation.dot(S.ldlt().solve(innovation)) > gate_chi2) {
      return false;  // the observation disagrees with the prediction: leave the state as it was
    }
    K.noalias() = PHt * S.inverse();
    const Eigen::VectorXd x_new = x_prior + K * innovation;
    for (std::size_t j = 0; j < count; ++j) {
      elements_[first + j] = Pose2(x_new.segment<3>(static_cast<Eigen::Index>(3 * j)));
    }
  }
  // P = (I - K H) P on the window, as the symmetric rank-d downdate P - K (P H^T)^T; the rest of
  // P is uncorrelated with the window and unchanged.
  P_.block(f, f, m, m).noalias() -= K * PHt.transpose();
  std::fill(group_start_.begin() + static_cast<long>(first), group_start_.end(), first);
  window_elements = std::max(window_elements, static_cast<int>(count));
  return true;
}

bool TrajectorySlam::update_match(std::size_t a, std::size_t b, const GaussianPose2& z,
                                  const Eigen::MatrixXd& observed, int& window_elements) {
  // z = spIC(scan_a, scan_b) observes h(X) = the pose of scan b in scan a (Eq. 5-8), in the
  // directions A = `observed` validated: A (z - h(X)), Jacobian A H, covariance A R A^T.
  const auto residual = [&](Eigen::MatrixXd* H) -> Eigen::VectorXd {
    Eigen::MatrixXd H_full;
    const Eigen::Vector3d r = pose_difference(z.mean, relative_pose(a, b, &H_full));
    *H = observed * H_full;
    return observed * r;
  };
  const Eigen::MatrixXd R = observed * z.cov * observed.transpose();
  return update(a + 1, b, residual, R,
                gate_for_dimensions(config_.innovation_gate_chi2, observed.rows()),
                window_elements);
}

bool TrajectorySlam::update_compass(std::size_t b, double yaw_world_rad, double sigma_rad,
                                    int& window_elements) {
  // z = the MRU heading observes the yaw of scan b in the world: start yaw + the chain's yaw.
  const auto residual = [&](Eigen::MatrixXd* H) -> Eigen::VectorXd {
    Eigen::MatrixXd H_pose;
    const Pose2 pose = pose_in_start_frame(b, &H_pose);
    *H = H_pose.row(2);
    return Eigen::VectorXd::Constant(
        1, normalize_angle(yaw_world_rad - start_world_.mean.yaw() - pose.yaw()));
  };
  const Eigen::MatrixXd R = Eigen::MatrixXd::Constant(1, 1, sigma_rad * sigma_rad);
  return update(0, b, residual, R, config_.compass_gate_chi2, window_elements);
}

}  // namespace msislab
