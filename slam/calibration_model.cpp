#include "slam/calibration_model.hpp"

#include <cmath>

namespace msislab {

ClockShifted clock_shifted(const Pose2& h, double tau_s, const Eigen::Vector3d& u_a,
                           const Eigen::Vector3d& u_b) {
  Eigen::Matrix3d J_inverse, J1_inner, J2_inner, J1, J2;
  const Pose2 back = Pose2(Eigen::Vector3d(tau_s * u_a)).inverse(&J_inverse);
  const Pose2 inner = back.compose(h, &J1_inner, &J2_inner);
  ClockShifted out;
  out.h = inner.compose(Pose2(Eigen::Vector3d(tau_s * u_b)), &J1, &J2);
  out.d_h = J1 * J2_inner;
  out.d_tau = J1 * J1_inner * J_inverse * u_a + J2 * u_b;
  return out;
}

CalibratedMotion calibrated_motion(const Pose2& m, std::optional<double> k,
                                   std::optional<Eigen::Vector2d> ab_rad,
                                   const Eigen::Vector2d& deviation_change) {
  CalibratedMotion out;
  out.d_m.setIdentity();
  out.d_k.setZero();
  out.d_ab.setZero();
  Eigen::Vector2d t = m.translation();
  double yaw = m.yaw();
  if (k) {
    // t / k, d/dk = -t_m / k^2.
    out.d_k.head<2>() = -t / (*k * *k);
    out.d_m.topLeftCorner<2, 2>() /= *k;
    t /= *k;
  }
  if (ab_rad) {
    // x = (R(-delta/2) t, yaw - delta); d(R(theta) t)/d theta = J R(theta) t.
    const double delta = ab_rad->dot(deviation_change);
    Eigen::Matrix2d R, J_turn;  // R(-delta/2)
    R << std::cos(delta / 2.0), std::sin(delta / 2.0), -std::sin(delta / 2.0),
        std::cos(delta / 2.0);
    J_turn << 0.0, -1.0, 1.0, 0.0;
    Eigen::Vector3d dx_ddelta;
    dx_ddelta << -0.5 * J_turn * R * t, -1.0;
    out.d_m.topRows<2>() = R * out.d_m.topRows<2>();
    out.d_k.head<2>() = R * out.d_k.head<2>();
    out.d_ab = dx_ddelta * deviation_change.transpose();
    t = R * t;
    yaw -= delta;
  }
  out.x = Pose2(t.x(), t.y(), yaw);
  return out;
}

}  // namespace msislab
