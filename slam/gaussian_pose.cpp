#include "slam/gaussian_pose.hpp"

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

}  // namespace msislab
