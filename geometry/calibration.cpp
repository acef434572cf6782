#include "geometry/calibration.hpp"

#include "geometry/angles.hpp"
#include "geometry/se2.hpp"

namespace msislab {

namespace {

/// d(psi) in radians.
double deviation_rad(double yaw_rad, const MruMount& mount) {
  return (mount.deviation_cos_deg * std::cos(yaw_rad) +
          mount.deviation_sin_deg * std::sin(yaw_rad)) *
         kDegToRad;
}

}  // namespace

double vehicle_yaw_from_mru(double yaw_mru_deg, const MruMount& mount) {
  const double read_rad = M_PI / 2.0 - (yaw_mru_deg - mount.yaw_offset_deg) * kDegToRad;
  // psi = read - d(psi): a contraction for deviations under 57 deg (|d'| < 1); a few degrees of
  // deviation converge to 1e-12 rad in well under 12 steps.
  double yaw_rad = read_rad;
  for (int i = 0; i < 12; ++i) yaw_rad = read_rad - deviation_rad(yaw_rad, mount);
  return normalize_angle(yaw_rad);
}

double mru_yaw_from_vehicle(double yaw_vehicle_rad, const MruMount& mount) {
  const double read_rad = yaw_vehicle_rad + deviation_rad(yaw_vehicle_rad, mount);
  return normalize_angle(M_PI / 2.0 - read_rad + mount.yaw_offset_deg * kDegToRad) / kDegToRad;
}

Eigen::Matrix2d R_vehicle_dvl(const DvlMount& mount) {
  const Eigen::Matrix2d R = Pose2(0.0, 0.0, mount.yaw_deg * kDegToRad).rotation();
  if (!mount.y_to_starboard) return R;
  return R * Eigen::Vector2d(1.0, -1.0).asDiagonal();  // the DVL's y mirrored, then rotated
}

double sonar_bearing_in_vehicle(double transducer_angle_rad, const SonarMount& mount) {
  return normalize_angle(mount.bearing_offset_rad + mount.bearing_sign * transducer_angle_rad);
}

}  // namespace msislab
