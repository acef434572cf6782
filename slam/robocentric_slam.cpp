#include "slam/robocentric_slam.hpp"

#include "geometry/pose_chain.hpp"
#include "slam/numerical_error.hpp"

namespace msislab {

void RoboCentricSlam::predict(const GaussianPose2& motion) {
  TrajectorySlam::predict(motion);  // e_k = x^{k-1}_k, not yet inverted (Eq. 2)
  newest_inverted_ = false;
}

void RoboCentricSlam::finish_step() {
  // Eq. 11-13: e_k <- (-)e_k; P <- J P J^T, J = diag(I, ..., I, J-): only row and column block k.
  observe_inversion_linearisation();
  const Eigen::Index k = element_row(elements_.size() - 1);
  Eigen::Matrix3d J_inverse;
  elements_.back() = elements_.back().inverse(&J_inverse);
  P_.middleRows<3>(k) = J_inverse * P_.middleRows<3>(k);
  P_.middleCols<3>(k) = P_.middleCols<3>(k) * J_inverse.transpose();
  newest_inverted_ = true;
}

Pose2 RoboCentricSlam::chain_pose(const std::vector<Pose2>& elements, std::size_t first,
                                  std::size_t b, Eigen::MatrixXd* H) const {
  // c = e_top (+) ... (+) e_first: scan first-1 seen from scan top, top = b, or b-1 while e_b is
  // still the raw motion; then h = (-)c, (+) e_b when raw.
  const bool raw = is_raw(b);
  const std::size_t top_plus_1 = raw ? b : b + 1;
  std::vector<Pose2> chain;
  for (std::size_t i = top_plus_1; i-- > first;) chain.push_back(elements[i]);
  std::vector<Eigen::Matrix3d> J_chain;
  const Pose2 c = compose_chain(chain, H ? &J_chain : nullptr);
  Eigen::Matrix3d J_inverse, J1, J2;
  const Pose2 g = c.inverse(H ? &J_inverse : nullptr);
  const Pose2 h = raw ? g.compose(elements[b], H ? &J1 : nullptr, H ? &J2 : nullptr) : g;
  if (H) {
    if (!raw) J1.setIdentity();
    H->resize(3, static_cast<Eigen::Index>(3 * (b - first + 1)));
    for (std::size_t m = 0; m < chain.size(); ++m) {
      const std::size_t element = top_plus_1 - 1 - m;
      H->middleCols<3>(static_cast<Eigen::Index>(3 * (element - first))) =
          J1 * J_inverse * J_chain[m];
    }
    if (raw) H->rightCols<3>() = J2;
  }
  return h;
}

Pose2 RoboCentricSlam::relative_pose_of(const std::vector<Pose2>& elements, std::size_t a,
                                        std::size_t b, Eigen::MatrixXd* H) const {
  return chain_pose(elements, a + 1, b, H);
}

Pose2 RoboCentricSlam::pose_in_start_frame_of(const std::vector<Pose2>& elements, std::size_t b,
                                              Eigen::MatrixXd* H) const {
  return chain_pose(elements, 0, b, H);
}

GaussianPose2 RoboCentricSlam::scan_pose_world(std::size_t i) const {
  Eigen::MatrixXd H;
  const Pose2 relative = chain_pose(elements_, 0, i, &H);
  return require_finite(compose(start_world_, GaussianPose2{relative, propagate(0, H)}),
                        "trajectory SLAM", i);
}

std::vector<double> RoboCentricSlam::newest_scan_distances_m() const {
  // Walk the chain back from the robot: c_j = e_{k-1} (+) ... (+) e_{j+1} is scan j seen from
  // scan k-1, and (-)e_k (+) c_j (or e_k (+) c_j once inverted) from scan k.
  const std::size_t k = elements_.size() - 1;
  const Pose2 newest_from_previous = is_raw(k) ? elements_[k].inverse() : elements_[k];
  std::vector<double> distances_m(elements_.size(), 0.0);
  Pose2 c;
  for (std::size_t j = k; j-- > 0;) {
    distances_m[j] = newest_from_previous.compose(c).translation().norm();
    c = c.compose(elements_[j]);
  }
  return distances_m;
}

}  // namespace msislab
