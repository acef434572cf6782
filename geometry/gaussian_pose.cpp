#include "geometry/gaussian_pose.hpp"

namespace msislab {

GaussianPose2 compose(const GaussianPose2& x_ab, const GaussianPose2& x_bc) {
  Eigen::Matrix3d J1;
  Eigen::Matrix3d J2;
  GaussianPose2 x_ac;
  x_ac.mean = x_ab.mean.compose(x_bc.mean, &J1, &J2);
  x_ac.cov = J1 * x_ab.cov * J1.transpose() + J2 * x_bc.cov * J2.transpose();
  return x_ac;
}

GaussianPose2 invert(const GaussianPose2& x_ab) {
  Eigen::Matrix3d J;
  GaussianPose2 x_ba;
  x_ba.mean = x_ab.mean.inverse(&J);
  x_ba.cov = J * x_ab.cov * J.transpose();
  return x_ba;
}

GaussianPose2 between(const Pose2& x_ab, const Pose2& x_ac,
                      const Eigen::Matrix<double, 6, 6>& joint_cov) {
  Eigen::Matrix3d J_ab;
  Eigen::Matrix3d J_ac;
  GaussianPose2 x_bc;
  x_bc.mean = x_ab.between(x_ac, &J_ab, &J_ac);
  Eigen::Matrix<double, 3, 6> J;
  J << J_ab, J_ac;
  const Eigen::Matrix3d cov = J * joint_cov * J.transpose();
  x_bc.cov = 0.5 * (cov + cov.transpose());
  return x_bc;
}

}  // namespace msislab
