// Navigation measurements after calibration: what the dead reckoning consumes, whatever the source
// (real logs or the simulator).
#pragma once

#include <Eigen/Core>
#include <vector>

namespace msislab {

/// DVL bottom velocity with bottom lock, in vehicle axes, measured at the DVL's mount point.
struct DvlVelocity {
  double t_s = 0.0;
  Eigen::Vector2d v_vehicle_mps = Eigen::Vector2d::Zero();
};

/// Vehicle yaw in the world frame from the heading unit (MRU).
struct HeadingReading {
  double t_s = 0.0;
  double yaw_rad = 0.0;
};

/// Time-ordered navigation measurements of one dataset.
struct NavigationLog {
  std::vector<DvlVelocity> dvl;
  std::vector<HeadingReading> heading;
  int dvl_rows_without_bottom_lock = 0;  ///< DVL rows dropped when the log was read
};

/// The heading reading nearest in time to t_s (ties go to the earlier). Requires a non-empty,
/// time-ordered list.
const HeadingReading& nearest_heading(const std::vector<HeadingReading>& heading, double t_s);

}  // namespace msislab
