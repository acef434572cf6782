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

/// What a scenario's rays give, traced once: the sonar's echoes on every beam before speckle and
/// noise, and the DVL's altitude at each sample. The vehicle follows its path without a random
/// draw, so both are the same for every seed: the runs of a Monte Carlo test trace them once and
/// share them.
struct ScenarioTrace {
  std::vector<BeamEchoes> beams;
  std::vector<double> dvl_altitude_m;
};
ScenarioTrace trace_scenario(const Scenario& scenario, const Scene& scene, int threads);

/// simulate() from a trace instead of the scene: the same bytes, when `trace` is
/// trace_scenario() of this scenario or of one that differs from it only in its seed.
/// std::invalid_argument when its beams or DVL samples are not this scenario's.
SimulationResult simulate(const Scenario& scenario, const ScenarioTrace& trace, int threads);

}  // namespace msislab::sim
