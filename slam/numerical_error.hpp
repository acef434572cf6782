// A filter's state or covariance that became NaN or infinite: the run cannot go on, and nothing
// estimated from that step on would be valid, so the estimator stops there with a message naming
// the scan, its time and the stage (prediction, compass or match update, solve). The command ends
// with that message (exit 1); a Monte Carlo run records it as the method's failure.
#pragma once

#include <cstddef>
#include <stdexcept>
#include <string>

#include "geometry/gaussian_pose.hpp"

namespace msislab {

class NumericalError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

/// Throws NumericalError "<estimator>: scan <scan> (t = <t_s> s): the state or its covariance is
/// not finite after the <stage>" unless `finite` ("pose <n>" with item "pose", for dead
/// reckoning). The estimators check their state after each stage of a step.
inline void require_finite(bool finite, const char* estimator, std::size_t scan, double t_s,
                           const char* stage, const char* item = "scan") {
  if (finite) return;
  throw NumericalError(std::string(estimator) + ": " + item + " " + std::to_string(scan) +
                       " (t = " + std::to_string(t_s) +
                       " s): the state or its covariance is not finite after the " + stage);
}

/// Throws NumericalError "<estimator>: scan <scan>: its world pose or covariance is not finite"
/// unless the pose read out of the state is finite (a read-out can overflow where the state did
/// not). Returns the pose.
inline const GaussianPose2& require_finite(const GaussianPose2& pose_world, const char* estimator,
                                           std::size_t scan) {
  if (pose_world.mean.vector().allFinite() && pose_world.cov.allFinite()) return pose_world;
  throw NumericalError(std::string(estimator) + ": scan " + std::to_string(scan) +
                       ": its world pose or covariance is not finite");
}

}  // namespace msislab
