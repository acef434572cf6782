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

}  // namespace msislab::sim
