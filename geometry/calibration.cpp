#include "geometry/calibration.hpp"

#include "geometry/se2.hpp"

namespace msislab {

namespace {
constexpr double kDegToRad = M_PI / 180.0;
}

double vehicle_yaw_from_mru(double yaw_mru_deg, const MruMount& mount) {
  return normalize_angle(M_PI / 2.0 - (yaw_mru_deg - mount.yaw_offset_deg) * kDegToRad);
}

double mru_yaw_from_vehicle(double yaw_vehicle_rad, const MruMount& mount) {
  return normalize_angle(M_PI / 2.0 - yaw_vehicle_rad + mount.yaw_offset_deg * kDegToRad) /
         kDegToRad;
}

Eigen::Matrix2d R_vehicle_dvl(const DvlMount& mount) {
  return Pose2(0.0, 0.0, mount.yaw_deg * kDegToRad).rotation();
}

double sonar_bearing_in_vehicle(double transducer_angle_rad, const SonarMount& mount) {
  return normalize_angle(mount.bearing_offset_rad + mount.bearing_sign * transducer_angle_rad);
}

}  // namespace msislab
