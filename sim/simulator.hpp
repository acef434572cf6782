// One simulation run: the vehicle's truth, every sonar beam (rendered in parallel, each from its
// own random stream, so the result does not depend on the thread count) and the navigation sensors.
#pragma once

#include <vector>

#include "sim/msis.hpp"
#include "sim/navigation_sensors.hpp"
#include "sim/scenario.hpp"
#include "sim/scene.hpp"
#include "sim/vehicle.hpp"

namespace msislab::sim {

struct SimulationResult {
  VehicleTrajectory truth;
  std::vector<RenderedBeam> beams;
  std::vector<DvlSample> dvl;
  std::vector<MruSample> mru;
  std::vector<GpsFix> gps;
};

/// Runs a scenario on a scene with `threads` worker threads (>= 1).
SimulationResult simulate(const Scenario& scenario, const Scene& scene, int threads);

/// The sonar's echoes on every beam of a scenario, before speckle and noise. The vehicle follows
/// its path without a random draw, so they are the same for every seed: the runs of a Monte Carlo
/// test trace them once and share them.
struct SonarEchoes {
  std::vector<BeamEchoes> beams;
};
SonarEchoes trace_sonar(const Scenario& scenario, const Scene& scene, int threads);

/// simulate(), with the sonar's beams received from `echoes` instead of traced again: the same
/// bytes, when `echoes` is trace_sonar() of this scenario or of one that differs from it only in
/// its seed. std::invalid_argument when their beams are not this scenario's.
SimulationResult simulate(const Scenario& scenario, const Scene& scene, const SonarEchoes& echoes,
                          int threads);

}  // namespace msislab::sim
