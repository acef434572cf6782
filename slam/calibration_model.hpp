// The calibration's measurement models, one for every back end (the filters' states,
// slam/trajectory_slam.hpp; the pose graph's blocks and its online belief, slam/pose_graph*.hpp;
// docs/trajectory_slam.md, "Calibration states"): how the sonar clock's offset moves what a match
// sees, and how the DVL's scale and the compass's deviation enter a dead-reckoning motion. Each
// with its Jacobians, checked against central differences in tests/slam/calibration_states_test.cpp
// and tests/slam/pose_graph_deviation_test.cpp.
#pragma once

#include <Eigen/Core>
#include <cmath>
#include <optional>

#include "geometry/se2.hpp"

namespace msislab {

/// A relative pose as scans seen tau late show it.
struct ClockShifted {
  Pose2 h;                ///< h_tau
  Eigen::Matrix3d d_h;    ///< dh_tau / dh
  Eigen::Vector3d d_tau;  ///< dh_tau / dtau
};

/// The pose h of scan b seen from scan a, as scans whose beams were sent tau_s later than their
/// times say show it: scan i shows the vehicle at t_i + tau, its frame moved by tau u_i (u_i the
/// scan's velocity, Scan::velocity_vehicle), so h_tau = (-)(tau u_a) (+) h (+) (tau u_b). With J1,
/// J2 of the outer composition, J1', J2' of the inner one and J- of the inversion: dh_tau/dh =
/// J1 J2', dh_tau/dtau = J1 J1' J- u_a + J2 u_b.
ClockShifted clock_shifted(const Pose2& h, double tau_s, const Eigen::Vector3d& u_a,
                           const Eigen::Vector3d& u_b);

/// The compass's one-cycle deviation d(psi) = a cos(psi) + b sin(psi) at the heading psi, rad.
inline double compass_deviation_rad(const Eigen::Vector2d& ab_rad, double psi_rad) {
  return ab_rad.dot(Eigen::Vector2d(std::cos(psi_rad), std::sin(psi_rad)));
}

/// A dead-reckoning motion as the state takes it in, with its Jacobians.
struct CalibratedMotion {
  Pose2 x;                           ///< the true motion the measured one stands for
  Eigen::Matrix3d d_m;               ///< dx / dm (the measured motion's noise)
  Eigen::Vector3d d_k;               ///< dx / dk (zero without the DVL's scale)
  Eigen::Matrix<double, 3, 2> d_ab;  ///< dx / d(a, b) (zero without the deviation)
};

/// The true motion x = g(c, m) behind a measured one m = (t, yaw):
/// - through the DVL's scale k (it measured k times the true velocity): t / k;
/// - through the compass's deviation (a, b): the heading change read delta = d(psi_1) - d(psi_0)
///   = (a, b) . deviation_change too much, and the translation, integrated along headings off by
///   a part of it growing from 0 to delta, turned by delta / 2 (to first order): (R(-delta / 2)
///   t, yaw - delta); deviation_change = (cos psi_1 - cos psi_0, sin psi_1 - sin psi_0) of the
///   motion's end and start headings (its start's term zero when the start is exact).
CalibratedMotion calibrated_motion(const Pose2& m, std::optional<double> k,
                                   std::optional<Eigen::Vector2d> ab_rad,
                                   const Eigen::Vector2d& deviation_change);

}  // namespace msislab
