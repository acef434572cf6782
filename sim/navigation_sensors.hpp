// Simulated navigation sensors sampled from the true trajectory, each with its own random stream:
// DVL bottom velocity (white noise, bias, dropouts, altitude from the scene), MRU heading (white
// noise plus a bias random walk) and a GPS buoy (white noise).
#pragma once

#include <Eigen/Core>
#include <cstdint>
#include <vector>

#include "sim/scenario.hpp"
#include "sim/scene.hpp"
#include "sim/vehicle.hpp"

namespace msislab::sim {

struct DvlSample {
  double t_s = 0.0;
  Eigen::Vector2d v_dvl_mps = Eigen::Vector2d::Zero();  ///< bottom velocity in the DVL frame
  bool bottom_lock = false;
  double altitude_m = 0.0;  ///< range to the bottom below the vehicle (0 when none in range)
};

struct MruSample {
  double t_s = 0.0;
  double yaw_mru_deg = 0.0;  ///< the heading unit's own reading (see MruMount)
};

struct GpsFix {
  double t_s = 0.0;
  Eigen::Vector2d p_world_m = Eigen::Vector2d::Zero();
};

std::vector<DvlSample> simulate_dvl(const VehicleTrajectory& truth, const DvlConfig& dvl,
                                    const Scene& scene, double depth_m, std::uint64_t seed);
std::vector<MruSample> simulate_mru(const VehicleTrajectory& truth, const MruConfig& mru,
                                    std::uint64_t seed);
std::vector<GpsFix> simulate_gps(const VehicleTrajectory& truth, const GpsConfig& gps,
                                 std::uint64_t seed);

}  // namespace msislab::sim
