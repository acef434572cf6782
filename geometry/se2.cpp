#include "geometry/se2.hpp"

#include <cmath>

namespace msislab {

double normalize_angle(double angle_rad) {
  // Most angles are already in range: return them untouched (remainder() would too, exactly).
  if (angle_rad > -M_PI && angle_rad <= M_PI) return angle_rad;
  // remainder() maps to [-pi, pi]; -pi is folded onto +pi so the range is (-pi, pi].
  double wrapped = std::remainder(angle_rad, 2.0 * M_PI);
  if (wrapped <= -M_PI) wrapped += 2.0 * M_PI;
  return wrapped;
}

Pose2::Pose2(double x_m, double y_m, double yaw_rad)
    : x_m_(x_m), y_m_(y_m), yaw_rad_(normalize_angle(yaw_rad)) {}

Pose2::Pose2(const Eigen::Vector3d& xyyaw) : Pose2(xyyaw.x(), xyyaw.y(), xyyaw.z()) {}

Eigen::Matrix2d Pose2::rotation() const {
  const double c = std::cos(yaw_rad_);
  const double s = std::sin(yaw_rad_);
  Eigen::Matrix2d R;
  R << c, -s, s, c;
  return R;
}

Pose2 Pose2::compose(const Pose2& x_bc, Eigen::Matrix3d* J_out_ab,
                     Eigen::Matrix3d* J_out_bc) const {
  const double c = std::cos(yaw_rad_);
  const double s = std::sin(yaw_rad_);
  // x_ac = [x_ab + c x_bc - s y_bc, y_ab + s x_bc + c y_bc, yaw_ab + yaw_bc]
  const double dx_a = c * x_bc.x_m_ - s * x_bc.y_m_;
  const double dy_a = s * x_bc.x_m_ + c * x_bc.y_m_;
  if (J_out_ab) {
    // J1+ = [1 0 -dy_a; 0 1 dx_a; 0 0 1]
    *J_out_ab << 1.0, 0.0, -dy_a, 0.0, 1.0, dx_a, 0.0, 0.0, 1.0;
  }
  if (J_out_bc) {
    // J2+ = [R(yaw_ab) 0; 0 1]
    *J_out_bc << c, -s, 0.0, s, c, 0.0, 0.0, 0.0, 1.0;
  }
  return {x_m_ + dx_a, y_m_ + dy_a, yaw_rad_ + x_bc.yaw_rad_};
}

Pose2 Pose2::inverse(Eigen::Matrix3d* J_out_ab) const {
  const double c = std::cos(yaw_rad_);
  const double s = std::sin(yaw_rad_);
  // x_ba = [-x c - y s, x s - y c, -yaw]
  const double x_ba = -x_m_ * c - y_m_ * s;
  const double y_ba = x_m_ * s - y_m_ * c;
  if (J_out_ab) {
    // J- = [-c -s y_ba; s -c -x_ba; 0 0 -1]
    *J_out_ab << -c, -s, y_ba, s, -c, -x_ba, 0.0, 0.0, -1.0;
  }
  return {x_ba, y_ba, -yaw_rad_};
}

Pose2 Pose2::between(const Pose2& x_ac, Eigen::Matrix3d* J_out_ab,
                     Eigen::Matrix3d* J_out_ac) const {
  Eigen::Matrix3d J_inv;
  Eigen::Matrix3d J_ba;
  const Pose2 x_ba = inverse(J_out_ab ? &J_inv : nullptr);
  const Pose2 x_bc = x_ba.compose(x_ac, J_out_ab ? &J_ba : nullptr, J_out_ac);
  if (J_out_ab) *J_out_ab = J_ba * J_inv;
  return x_bc;
}

Eigen::Vector2d Pose2::transform(const Eigen::Vector2d& p_b, Matrix23d* J_out_pose,
                                 Eigen::Matrix2d* J_out_point) const {
  const Eigen::Matrix2d R = rotation();
  const Eigen::Vector2d Rp = R * p_b;
  if (J_out_pose) {
    // d p_a / d [x y yaw] = [1 0 -(R p)_y; 0 1 (R p)_x]
    *J_out_pose << 1.0, 0.0, -Rp.y(), 0.0, 1.0, Rp.x();
  }
  if (J_out_point) *J_out_point = R;
  return Rp + translation();
}

Eigen::Vector3d pose_difference(const Pose2& a, const Pose2& b) {
  return {a.x() - b.x(), a.y() - b.y(), normalize_angle(a.yaw() - b.yaw())};
}

}  // namespace msislab
