// TUM trajectory files: "t x y z qx qy qz qw" per line, '#' comments. msislab poses are planar:
// z = -depth and the quaternion is a rotation about z, q = (0, 0, sin(yaw/2), cos(yaw/2)).
#pragma once

#include <string>
#include <vector>

namespace msislab::io {

struct TumPose {
  double t_s = 0.0;
  double x_m = 0.0;
  double y_m = 0.0;
  double z_m = 0.0;
  double yaw_rad = 0.0;  ///< from the quaternion's rotation about z
};

/// Reads a TUM file; the yaw is extracted from the quaternion (which is normalised first; a zero
/// quaternion is an error). Times must increase.
std::vector<TumPose> read_tum(const std::string& path);
/// Writes a TUM file atomically with full double precision.
void write_tum(const std::string& path, const std::vector<TumPose>& poses);
/// The yaw read_tum() gives back for a pose written with this yaw: through its quaternion, so
/// the last bits may differ. A trajectory held in memory in place of a file carries this.
double yaw_as_stored(double yaw_rad);

}  // namespace msislab::io
