// The simulated vehicle: pure-pursuit path following at constant depth, at a constant speed or one
// speed per leg, with a bounded turn rate, integrated at a fine step into the exact truth
// trajectory.
#pragma once

#include <vector>

#include "geometry/se2.hpp"
#include "sim/scenario.hpp"

namespace msislab::sim {

struct VehicleState {
  double t_s = 0.0;
  Pose2 pose;              ///< vehicle in the scene frame
  double surge_mps = 0.0;  ///< u, vehicle frame
  double sway_mps = 0.0;   ///< v, vehicle frame
  double yaw_rate_radps = 0.0;
};

class VehicleTrajectory {
 public:
  explicit VehicleTrajectory(std::vector<VehicleState> samples);

  /// The state at t_s (linear between samples, yaw along the short arc); clamped to the span.
  VehicleState at(double t_s) const;
  double start_s() const { return samples_.front().t_s; }
  double end_s() const { return samples_.back().t_s; }
  const std::vector<VehicleState>& samples() const { return samples_; }

 private:
  std::vector<VehicleState> samples_;
};

/// Follows config.path_m (>= 2 waypoints) from the first waypoint, heading along the first leg,
/// until the last waypoint is reached; with config.heading_deg, pointing that way instead
/// (with_heading).
VehicleTrajectory follow_path(const VehicleConfig& config);

/// The same positions and world velocities, the vehicle pointing at heading_deg (rows of t_s from
/// the trajectory's start and yaw_deg, >= 2, time-ordered; interpolated along the short arc and
/// held beyond its ends): surge and sway are the world velocity in the new vehicle axes, the yaw
/// rate the heading's central difference over the samples.
VehicleTrajectory with_heading(const VehicleTrajectory& course,
                               const std::vector<Eigen::Vector2d>& heading_deg);

}  // namespace msislab::sim
