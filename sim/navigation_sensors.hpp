// Simulated navigation sensors sampled from the true trajectory, each with its own random stream:
// DVL bottom velocity (heavy-tailed white noise, bias, bursty dropouts, altitude from the scene),
// MRU heading (white noise plus a bias random walk) and a GPS on a towed buoy (Gauss-Markov error
// plus white noise). docs/simulator.md gives the equations and where the defaults come from.
#pragma once

#include <Eigen/Core>
#include <cstdint>
#include <vector>

#include "geometry/navigation_noise.hpp"
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
/// The DVL's altitude above the bottom at each of its sample times (0: no bottom within its
/// range): the scene's part of the DVL, with no random draw in it.
std::vector<double> dvl_altitudes(const VehicleTrajectory& truth, const DvlConfig& dvl,
                                  const Scene& scene, double depth_m);
/// simulate_dvl with the altitudes of dvl_altitudes() given: the same samples.
std::vector<DvlSample> simulate_dvl(const VehicleTrajectory& truth, const DvlConfig& dvl,
                                    const std::vector<double>& altitudes_m, std::uint64_t seed);
std::vector<MruSample> simulate_mru(const VehicleTrajectory& truth, const MruConfig& mru,
                                    std::uint64_t seed);
/// The towed buoy's step: it stays put while within tether_m of the vehicle, else it is dragged
/// along the line to it, p_b <- p_v + L (p_b - p_v) / |p_b - p_v|.
Eigen::Vector2d drag_buoy(const Eigen::Vector2d& p_buoy_m, const Eigen::Vector2d& p_vehicle_m,
                          double tether_m);
std::vector<GpsFix> simulate_gps(const VehicleTrajectory& truth, const GpsConfig& gps,
                                 std::uint64_t seed);

/// The scenario's navigation errors in the dead reckoning's terms, for its dataset to carry: the
/// DVL's contaminated normal by its standard deviation, sqrt((1 - p) s^2 + p s_o^2); the MRU's
/// white noise and bias walk as they are; and the constants the dataset's calibration.yaml does
/// not state (the MRU's initial bias, the DVL scale factor beyond the stated one) by their size,
/// as one standard deviation of an unknown constant. Mounts, deviation, clock offset and range
/// scale are calibration (the filters' states), not noise; the DVL's constant bias_mps and its
/// dropouts are not modelled by the dead reckoning and are left out.
NavigationNoise navigation_noise_of(const Scenario& scenario);

}  // namespace msislab::sim
