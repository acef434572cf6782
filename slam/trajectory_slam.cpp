#include "slam/trajectory_slam.hpp"

#include <Eigen/Cholesky>
#include <Eigen/LU>
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <limits>

#include "slam/iterated_ekf.hpp"
#include "slam/numerical_error.hpp"

namespace msislab {

MatchRecord record_of(std::size_t j, std::size_t k, const ValidatedMatch& m,
                      const GaussianPose2& predicted, double nis) {
  MatchRecord record;
  record.scan = k;
  record.reference = j;
  record.valid = m.match.valid;
  record.rejection = m.rejection;
  record.observed = m.observed;
  record.restarts = m.restarts;
  record.z = m.match.estimate;
  record.predicted = predicted;
  record.nis = nis;
  return record;
}

void MatchRejectionCounts::count(const ValidatedMatch& match) {
  if (match.rejection == MatchRejection::kNone) {
    direction_dropped += match.direction_dropped;
  } else {
    ++rejected[static_cast<std::size_t>(match.rejection)];
  }
}

void TrajectorySlam::predict(const GaussianPose2& motion) {
  const Eigen::Index n = P_.rows();
  P_.conservativeResize(n + 3, n + 3);
  P_.rightCols<3>().setZero();
  P_.bottomRows<3>().setZero();
  if (calibration_.size() == 0) {
    elements_.push_back(motion.mean);
    P_.bottomRightCorner<3, 3>() = motion.cov;
    return;
  }
  // x = g(c, m), appended correlated with the calibration: P_xX = dg/dc P_cX.
  Eigen::Matrix3d J_m;
  Eigen::MatrixXd J_c;
  elements_.push_back(calibrated_motion(motion.mean, J_m, J_c));
  const Eigen::Index c = calibration_.size();
  P_.bottomLeftCorner(3, n) = J_c * P_.topLeftCorner(c, n);
  P_.topRightCorner(n, 3) = P_.bottomLeftCorner(3, n).transpose();
  P_.bottomRightCorner<3, 3>() =
      J_m * motion.cov * J_m.transpose() + J_c * P_.topLeftCorner(c, c) * J_c.transpose();
}

Eigen::Matrix3d TrajectorySlam::propagate(std::size_t first, const Eigen::MatrixXd& J) const {
  const Eigen::Index f = element_row(first);
  return J * P_.block(f, f, J.cols(), J.cols()) * J.transpose();
}

bool TrajectorySlam::state_finite() const {
  for (const Pose2& element : elements_) {
    if (!element.vector().allFinite()) return false;
  }
  return P_.allFinite();
}

void TrajectorySlam::predict_scan(const Scan& scan, const GaussianPose2& motion) {
  walk_heading_bias(scan.t_s);
  note_deviation_change(scan.compass_yaw_world_rad);
  predict(motion);
  group_start_.push_back(elements_.size() - 1);
  require_finite(state_finite(), "trajectory SLAM", elements_.size() - 1, scan.t_s, "prediction");
}

bool TrajectorySlam::update_compass_reading(const Scan& scan, SlamStepStats& stats) {
  const std::size_t k = elements_.size() - 1;
  const std::optional<std::size_t> window =
      update_compass(k, scan.compass_yaw_world_rad, scan.compass_sigma_rad);
  if (!window) return false;
  stats.note_window(*window);
  require_finite(state_finite(), "trajectory SLAM", k, scan.t_s, "compass update");
  return true;
}

void TrajectorySlam::update_with_matches(std::size_t k, const ScanCandidates& candidates,
                                         const Scan& scan, SlamStepStats& stats) {
  // Observe and update (Eq. 5-10): one match after the other, or all together (Eq. 8).
  std::vector<std::size_t> references;
  for (const auto& candidate : candidates) references.push_back(candidate.second);
  if (config_.front_end.joint_update) {
    update_jointly(k, references, stats);
  } else {
    update_sequentially(k, references, stats);
  }
  if (stats.accepted > 0)
    require_finite(state_finite(), "trajectory SLAM", k, scan.t_s, "match updates");
  for (std::size_t c = 0; c < stats.matches.size(); ++c) {
    stats.matches[c].distance_m = candidates[c].first;
  }
}

void TrajectorySlam::finish_scan_step(std::size_t /*k*/, const Scan& /*scan*/) {
  finish_step();
  observe_pose_linearisation();
}

void TrajectorySlam::observe_pose_linearisation() const {
  if (!observer_) return;
  const std::size_t k = elements_.size() - 1;
  Eigen::MatrixXd H;
  const Pose2 pose_hat = pose_in_start_frame(k, &H);
  Eigen::VectorXd x_hat(static_cast<Eigen::Index>(3 * elements_.size()));
  for (std::size_t j = 0; j < elements_.size(); ++j) {
    x_hat.segment<3>(static_cast<Eigen::Index>(3 * j)) = elements_[j].vector();
  }
  std::vector<Pose2> sample(elements_.size());
  const Deviation deviation = [&](const Eigen::VectorXd& x) -> Eigen::VectorXd {
    for (std::size_t j = 0; j < sample.size(); ++j) {
      sample[j] = Pose2(Eigen::Vector3d(x.segment<3>(static_cast<Eigen::Index>(3 * j))));
    }
    return pose_difference(pose_in_start_frame_of(sample, k, nullptr), pose_hat);
  };
  const Eigen::MatrixXd P_elements = P_.bottomRightCorner(x_hat.size(), x_hat.size());
  observer_->linearised(Linearisation::kPose, deviation, x_hat, P_elements, H, propagate(0, H));
}

void TrajectorySlam::observe_inversion_linearisation() const {
  if (!observer_) return;
  const Pose2 e_hat = elements_.back();
  const Eigen::Index k = element_row(elements_.size() - 1);
  Eigen::Matrix3d J;
  const Pose2 inverse_hat = e_hat.inverse(&J);
  const Eigen::Matrix3d P_e = P_.block<3, 3>(k, k);
  const Deviation deviation = [&](const Eigen::VectorXd& x) -> Eigen::VectorXd {
    return pose_difference(Pose2(Eigen::Vector3d(x)).inverse(), inverse_hat);
  };
  observer_->linearised(Linearisation::kInversion, deviation, e_hat.vector(), P_e, J,
                        J * P_e * J.transpose());
}

template <class Residual>
void TrajectorySlam::observe_observation_linearisation(std::size_t first_involved, std::size_t b,
                                                       const Residual& residual,
                                                       const Eigen::VectorXd& z_minus_h,
                                                       const Eigen::VectorXd& x_involved,
                                                       const Eigen::MatrixXd& P_involved,
                                                       const Eigen::MatrixXd& H_involved,
                                                       const Eigen::MatrixXd& S) const {
  // h of the involved elements first_involved..b, sampled on a copy of the state (at the prior
  // here): A (h(X) - h(X^)) = r(X^) - r(X).
  std::vector<Pose2> sample = elements_;
  const Deviation deviation = [&](const Eigen::VectorXd& x) -> Eigen::VectorXd {
    for (std::size_t j = first_involved; j <= b; ++j) {
      sample[j] =
          Pose2(Eigen::Vector3d(x.segment<3>(static_cast<Eigen::Index>(3 * (j - first_involved)))));
    }
    return z_minus_h - residual(sample, nullptr);
  };
  observer_->linearised(Linearisation::kObservation, deviation, x_involved, P_involved, H_involved,
                        S);
}

template <class Residual>
std::optional<std::size_t> TrajectorySlam::update(std::size_t first_involved, std::size_t b,
                                                  const Residual& residual,
                                                  const Eigen::MatrixXd& R, double gate_chi2,
                                                  bool observe_linearisation) {
  // The window: from the start of the group holding the first involved element to b (the newest
  // element), which takes in every element correlated with the ones h depends on. Calibration
  // states correlate with every element: the window is then the whole state, the calibration
  // first (P's first c rows).
  const Eigen::Index c = calibration_.size();
  const std::size_t first =
      config_.filter.update_whole_state || c > 0 ? 0 : group_start_[first_involved];
  const std::size_t count = b + 1 - first;
  const Eigen::Index m = c + static_cast<Eigen::Index>(3 * count);
  const Eigen::Index f = static_cast<Eigen::Index>(3 * first);  // 0 whenever c > 0
  const Eigen::Index h_col = c + static_cast<Eigen::Index>(3 * (first_involved - first));
  const Eigen::Index d = R.rows();
  const auto P_window = P_.block(f, f, m, m);

  // Iterated EKF (paper Eq. 9-10, slam/iterated_ekf.hpp) on the window, h's Jacobian placed at
  // the calibration's and the involved elements' columns.
  Eigen::MatrixXd H_involved, K, PHt;
  const auto residual_window = [&](Eigen::MatrixXd* H) -> Eigen::VectorXd {
    const Eigen::VectorXd z_minus_h = residual(elements_, &H_involved);
    H->setZero(d, m);
    H->leftCols(c) = H_involved.leftCols(c);
    H->middleCols(h_col, H_involved.cols() - c) = H_involved.rightCols(H_involved.cols() - c);
    return z_minus_h;
  };
  const auto at_first = [&](const Eigen::VectorXd& x_prior, const Eigen::VectorXd& z_minus_h,
                            const Eigen::VectorXd& innovation, const Eigen::MatrixXd& S) {
    if (innovation.dot(S.ldlt().solve(innovation)) > gate_chi2) {
      return false;  // the observation disagrees with the prediction: leave the state as it was
    }
    if (observe_linearisation && observer_) {
      const Eigen::Index n = m - h_col;
      observe_observation_linearisation(first_involved, b, residual, z_minus_h, x_prior.tail(n),
                                        P_window.bottomRightCorner(n, n), H_involved.rightCols(n),
                                        S);
    }
    return true;
  };
  if (!iterated_ekf_update(calibration_, elements_.begin() + static_cast<long>(first), count,
                           P_window, residual_window, R, config_.front_end.iekf_iterations,
                           at_first, K, PHt)) {
    return std::nullopt;
  }
  // P = (I - K H) P on the window, as the symmetric rank-d downdate P - K (P H^T)^T; the rest of
  // P is uncorrelated with the window and unchanged.
  P_.block(f, f, m, m).noalias() -= K * PHt.transpose();
  std::fill(group_start_.begin() + static_cast<long>(first), group_start_.end(), first);
  return count;
}

void TrajectorySlam::update_sequentially(std::size_t k, const std::vector<std::size_t>& candidates,
                                         SlamStepStats& stats) {
  for (const std::size_t j : candidates) {
    GaussianPose2 predicted;
    ValidatedMatch m = match(j, k, predicted);  // from the state the previous update left
    if (m.match.valid) ++stats.matched;
    double nis = std::numeric_limits<double>::quiet_NaN();
    if (m.rejection == MatchRejection::kNone) {
      std::vector<RelativePoseObservation::SharedError> shared;
      const Eigen::MatrixXd R =
          m.observed * match_noise(j, k, m.match, &shared) * m.observed.transpose();
      const std::vector<RelativePoseObservation> z = {
          {j, m.match.estimate.mean, m.observed, shared}};
      nis = innovation_nis(k, z, R);
      if (const std::optional<std::size_t> window = update_relative_poses(k, z, R)) {
        stats.note_window(*window);
        ++stats.accepted;
      } else {
        m.rejection = MatchRejection::kInnovation;
      }
    }
    stats.matches.push_back(record_of(j, k, m, predicted, nis));
    stats.rejections.count(m);
    totals_.rejections.count(m);
  }
}

// match and the observation model: slam/trajectory_observations.cpp; update_jointly, the same
// matches in one update (paper Eq. 8): slam/joint_update.cpp.

std::optional<std::size_t> TrajectorySlam::update_relative_poses(
    std::size_t b, const std::vector<RelativePoseObservation>& z, const Eigen::MatrixXd& R) {
  if (z.empty() || b >= elements_.size()) return std::nullopt;
  for (const RelativePoseObservation& o : z) {
    if (o.reference >= b) return std::nullopt;  // h is the pose of b in an earlier scan's frame
  }
  const auto residual = [&](const std::vector<Pose2>& elements, Eigen::MatrixXd* H) {
    return stacked_residual(elements, b, z, H);
  };
  return update(first_involved(b, z), b, residual, R,
                gate_for_dimensions(config_.front_end.innovation_gate_chi2, R.rows()), true);
}

std::optional<std::size_t> TrajectorySlam::update_compass(std::size_t b, double yaw_world_rad,
                                                          double sigma_rad) {
  const auto residual = [&](const std::vector<Pose2>& elements, Eigen::MatrixXd* H) {
    return compass_residual(elements, b, yaw_world_rad, H);
  };
  const Eigen::MatrixXd R = Eigen::MatrixXd::Constant(1, 1, sigma_rad * sigma_rad);
  // The chain's yaw is the sum of its elements' yaws (with a deviation, h is nearly linear):
  // nothing to measure.
  return update(0, b, residual, R, config_.front_end.compass_gate_chi2, false);
}

}  // namespace msislab
