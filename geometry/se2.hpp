// SE(2) pose algebra: the compounding (+) and inversion (-) operators of Smith, Self and Cheeseman
// with their Jacobians J1+, J2+ and J-. Every filter in msislab is written in terms of this type.
// Conventions and formulas: docs/pose_algebra.md.
#pragma once

#include <Eigen/Core>

namespace msislab {

using Matrix23d = Eigen::Matrix<double, 2, 3>;

/// Wraps an angle to (-pi, pi].
double normalize_angle(double angle_rad);

/// A planar pose x_ab = [x, y, yaw]: the frame b seen from the frame a (x forward, y to port,
/// yaw counter-clockwise). A point p_b in b is p_a = R(yaw) p_b + [x, y] in a.
class Pose2 {
 public:
  Pose2() = default;
  Pose2(double x_m, double y_m, double yaw_rad);
  /// From [x, y, yaw]; the angle is normalized.
  explicit Pose2(const Eigen::Vector3d& xyyaw);

  double x() const { return x_m_; }
  double y() const { return y_m_; }
  double yaw() const { return yaw_rad_; }
  Eigen::Vector2d translation() const { return {x_m_, y_m_}; }
  Eigen::Matrix2d rotation() const;
  Eigen::Vector3d vector() const { return {x_m_, y_m_, yaw_rad_}; }

  /// Compounding x_ac = x_ab (+) x_bc. J_out_ab = J1+, J_out_bc = J2+.
  Pose2 compose(const Pose2& x_bc, Eigen::Matrix3d* J_out_ab = nullptr,
                Eigen::Matrix3d* J_out_bc = nullptr) const;

  /// Inversion x_ba = (-) x_ab. J_out_ab = J-.
  Pose2 inverse(Eigen::Matrix3d* J_out_ab = nullptr) const;

  /// x_bc = (-) x_ab (+) x_ac: the pose of c seen from b, given both seen from a.
  Pose2 between(const Pose2& x_ac, Eigen::Matrix3d* J_out_ab = nullptr,
                Eigen::Matrix3d* J_out_ac = nullptr) const;

  /// Point compounding p_a = x_ab (+) p_b. J_out_pose is 2x3, J_out_point is 2x2.
  Eigen::Vector2d transform(const Eigen::Vector2d& p_b, Matrix23d* J_out_pose = nullptr,
                            Eigen::Matrix2d* J_out_point = nullptr) const;

 private:
  double x_m_ = 0.0;
  double y_m_ = 0.0;
  double yaw_rad_ = 0.0;
};

/// x_ab (+) x_bc.
inline Pose2 operator+(const Pose2& x_ab, const Pose2& x_bc) { return x_ab.compose(x_bc); }
/// (-) x_ab.
inline Pose2 operator-(const Pose2& x_ab) { return x_ab.inverse(); }

/// The difference a - b as a 3-vector with the angle wrapped: the error used by NEES and by
/// finite-difference checks.
Eigen::Vector3d pose_difference(const Pose2& a, const Pose2& b);

}  // namespace msislab
