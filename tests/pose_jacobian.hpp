// The numerical Jacobian the SE(2) tests hold the analytic ones against (tests/geometry).
#pragma once

#include <Eigen/Core>
#include <functional>

#include "geometry/se2.hpp"

namespace msislab::testing {

/// The central finite-difference step, m or rad.
inline constexpr double kFdStep = 1e-6;

/// Numerical Jacobian of a pose-valued function of a pose, by central differences; output
/// differences are taken with pose_difference so a yaw that wraps across +-pi does not produce a
/// 2 pi jump.
inline Eigen::Matrix3d numeric_jacobian(const std::function<Pose2(const Pose2&)>& f,
                                        const Pose2& x) {
  Eigen::Matrix3d J;
  for (int i = 0; i < 3; ++i) {
    const Eigen::Vector3d step = kFdStep * Eigen::Vector3d::Unit(i);
    const Pose2 plus(x.vector() + step);
    const Pose2 minus(x.vector() - step);
    J.col(i) = pose_difference(f(plus), f(minus)) / (2.0 * kFdStep);
  }
  return J;
}

}  // namespace msislab::testing
