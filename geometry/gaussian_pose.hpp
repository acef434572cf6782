// A pose with Gaussian uncertainty, and the first-order propagation of compounding and inversion
// (Smith, Self, Cheeseman): P_ac = J1+ P_ab J1+^T + J2+ P_bc J2+^T, P_ba = J- P_ab J-^T.
#pragma once

#include <Eigen/Core>

#include "geometry/se2.hpp"

namespace msislab {

struct GaussianPose2 {
  Pose2 mean;                                     ///< [x_m, y_m, yaw_rad]
  Eigen::Matrix3d cov = Eigen::Matrix3d::Zero();  ///< covariance of [x_m, y_m, yaw_rad]
};

/// x_ac = x_ab (+) x_bc for independent x_ab and x_bc.
GaussianPose2 compose(const GaussianPose2& x_ab, const GaussianPose2& x_bc);

/// x_ba = (-) x_ab.
GaussianPose2 invert(const GaussianPose2& x_ab);

/// x_bc = (-) x_ab (+) x_ac for x_ab and x_ac with joint covariance joint_cov (6 x 6: x_ab's
/// components, then x_ac's): P_bc = J P J^T with J = [J_ab J_ac] of Pose2::between. The cross
/// terms take out what the two poses share (two poses on one chain: the part before their fork).
GaussianPose2 between(const Pose2& x_ab, const Pose2& x_ac,
                      const Eigen::Matrix<double, 6, 6>& joint_cov);

/// A Gaussian pose at a time: one sample of a trajectory.
struct StampedPose {
  double t_s = 0.0;    ///< log time, Unix seconds
  GaussianPose2 pose;  ///< the vehicle in the world frame
};

}  // namespace msislab
