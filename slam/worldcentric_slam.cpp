#include "slam/worldcentric_slam.hpp"

#include "geometry/pose_chain.hpp"
#include "slam/numerical_error.hpp"

namespace msislab {

namespace {

/// The chain's Jacobian blocks side by side (3 x 3n).
Eigen::MatrixXd side_by_side(const std::vector<Eigen::Matrix3d>& J) {
  Eigen::MatrixXd H(3, static_cast<Eigen::Index>(3 * J.size()));
  for (std::size_t j = 0; j < J.size(); ++j)
    H.middleCols<3>(static_cast<Eigen::Index>(3 * j)) = J[j];
  return H;
}

}  // namespace

Pose2 WorldCentricSlam::relative_pose_of(const std::vector<Pose2>& elements, std::size_t a,
                                         std::size_t b, Eigen::MatrixXd* H) const {
  const std::vector<Pose2> chain(elements.begin() + static_cast<long>(a) + 1,
                                 elements.begin() + static_cast<long>(b) + 1);
  std::vector<Eigen::Matrix3d> J;
  const Pose2 pose = compose_chain(chain, H ? &J : nullptr);
  if (H) *H = side_by_side(J);
  return pose;
}

Pose2 WorldCentricSlam::pose_in_start_frame_of(const std::vector<Pose2>& elements, std::size_t b,
                                               Eigen::MatrixXd* H) const {
  const std::vector<Pose2> chain(elements.begin(), elements.begin() + static_cast<long>(b) + 1);
  std::vector<Eigen::Matrix3d> J;
  const Pose2 pose = compose_chain(chain, H ? &J : nullptr);
  if (H) *H = side_by_side(J);
  return pose;
}

GaussianPose2 WorldCentricSlam::scan_pose_world(std::size_t i) const {
  Eigen::MatrixXd H;
  const Pose2 relative = pose_in_start_frame(i, &H);
  return require_finite(compose(start_world_, GaussianPose2{relative, propagate(0, H)}),
                        "trajectory SLAM", i);
}

std::vector<double> WorldCentricSlam::newest_scan_distances_m() const {
  // Scan poses in the start frame, then each past one's distance to the newest.
  std::vector<Pose2> poses(elements_.size());
  Pose2 pose;
  for (std::size_t i = 0; i < elements_.size(); ++i) poses[i] = pose = pose.compose(elements_[i]);
  std::vector<double> distances_m(elements_.size());
  for (std::size_t j = 0; j < elements_.size(); ++j) {
    distances_m[j] = (poses.back().translation() - poses[j].translation()).norm();
  }
  return distances_m;
}

}  // namespace msislab
