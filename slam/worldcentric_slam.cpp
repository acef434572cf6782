#include "slam/worldcentric_slam.hpp"

#include <Eigen/Cholesky>
#include <Eigen/LU>
#include <algorithm>

#include "slam/pose_chain.hpp"

namespace msislab {

WorldCentricSlam::WorldCentricSlam(const TrajectorySlamConfig& config,
                                   const GaussianPose2& start_world)
    : config_(config), start_world_(start_world) {}

Pose2 WorldCentricSlam::relative_pose(std::size_t a, std::size_t b, Eigen::MatrixXd* H) const {
  // Scan i's frame is reached by x_0 (+) ... (+) x_i from the start, so scan b in scan a's frame
  // is x_{a+1} (+) ... (+) x_b.
  const std::vector<Pose2> chain(motions_.begin() + static_cast<long>(a) + 1,
                                 motions_.begin() + static_cast<long>(b) + 1);
  std::vector<Eigen::Matrix3d> J;
  const Pose2 pose = compose_chain(chain, H ? &J : nullptr);
  if (H) {
    *H = Eigen::MatrixXd::Zero(3, static_cast<Eigen::Index>(3 * motions_.size()));
    for (std::size_t j = 0; j < J.size(); ++j) {
      H->block<3, 3>(0, static_cast<Eigen::Index>(3 * (a + 1 + j))) = J[j];
    }
  }
  return pose;
}

GaussianPose2 WorldCentricSlam::scan_pose_world(std::size_t i) const {
  const std::vector<Pose2> chain(motions_.begin(), motions_.begin() + static_cast<long>(i) + 1);
  std::vector<Eigen::Matrix3d> J;
  const Pose2 relative = compose_chain(chain, &J);
  Eigen::MatrixXd H = Eigen::MatrixXd::Zero(3, static_cast<Eigen::Index>(3 * motions_.size()));
  for (std::size_t j = 0; j < J.size(); ++j) {
    H.block<3, 3>(0, static_cast<Eigen::Index>(3 * j)) = J[j];
  }
  return compose(start_world_, GaussianPose2{relative, H * P_ * H.transpose()});
}

SlamStepStats WorldCentricSlam::add_scan(const Scan& scan) {
  // Predict: append the new motion, uncorrelated with the past.
  const Eigen::Index n = static_cast<Eigen::Index>(3 * motions_.size());
  motions_.push_back(scan.motion.mean);
  points_.push_back(scan.points);
  P_.conservativeResize(n + 3, n + 3);
  P_.rightCols<3>().setZero();
  P_.bottomRows<3>().setZero();
  P_.bottomRightCorner<3, 3>() = scan.motion.cov;

  // Associate: past scans whose estimated centre is within gamma, nearest first.
  SlamStepStats stats;
  const std::size_t k = motions_.size() - 1;
  std::vector<std::pair<double, std::size_t>> candidates;
  for (std::size_t j = 0; j < k; ++j) {
    const double d = relative_pose(j, k, nullptr).translation().norm();
    if (d < config_.association_distance_m) candidates.emplace_back(d, j);
  }
  std::sort(candidates.begin(), candidates.end());
  if (static_cast<int>(candidates.size()) > config_.max_matches_per_scan) {
    candidates.resize(static_cast<std::size_t>(config_.max_matches_per_scan));
  }
  stats.candidates = static_cast<int>(candidates.size());
  for (const auto& [distance_m, j] : candidates) {
    Eigen::MatrixXd H;
    GaussianPose2 guess;
    guess.mean = relative_pose(j, k, &H);
    guess.cov = H * P_ * H.transpose();
    const ScanMatchResult match = match_scans(points_[j], points_[k], guess, config_.matching);
    if (!match.valid) continue;
    ++stats.matched;
    if (update(j, k, match.estimate)) ++stats.accepted;
  }
  return stats;
}

bool WorldCentricSlam::update(std::size_t a, std::size_t b, const GaussianPose2& z) {
  // Iterated EKF (paper Eq. 9-10): X_{i+1} = X^ + K_i (z - h(X_i) - H_i (X^ - X_i)),
  // K_i = P H_i^T (H_i P H_i^T + R)^-1; then P = (I - K H) P at the last linearisation.
  const Eigen::Index n = static_cast<Eigen::Index>(3 * motions_.size());
  const std::vector<Pose2> prior = motions_;
  Eigen::VectorXd x_prior(n);
  for (std::size_t j = 0; j < prior.size(); ++j) {
    x_prior.segment<3>(static_cast<Eigen::Index>(3 * j)) = prior[j].vector();
  }
  Eigen::MatrixXd H, K;
  for (int iteration = 0; iteration < std::max(1, config_.iekf_iterations); ++iteration) {
    const Pose2 h = relative_pose(a, b, &H);
    Eigen::VectorXd dx(n);  // X^ - X_i, angles wrapped
    for (std::size_t j = 0; j < prior.size(); ++j) {
      dx.segment<3>(static_cast<Eigen::Index>(3 * j)) = pose_difference(prior[j], motions_[j]);
    }
    const Eigen::Matrix3d S = H * P_ * H.transpose() + z.cov;
    const Eigen::Vector3d innovation = pose_difference(z.mean, h) - H * dx;
    if (iteration == 0 &&
        innovation.dot(S.ldlt().solve(innovation)) > config_.innovation_gate_chi2) {
      return false;  // the match disagrees with the prediction: leave the state as it was
    }
    K = P_ * H.transpose() * S.inverse();
    const Eigen::VectorXd x_new = x_prior + K * innovation;
    for (std::size_t j = 0; j < motions_.size(); ++j) {
      motions_[j] = Pose2(x_new.segment<3>(static_cast<Eigen::Index>(3 * j)));
    }
  }
  // P = (I - K H) P, as P - K (H P): O(n^2) instead of a dense n x n product.
  P_ -= K * (H * P_);
  P_ = 0.5 * (P_ + P_.transpose());
  return true;
}

}  // namespace msislab
