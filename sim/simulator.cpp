#include "sim/simulator.hpp"

#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

#include <algorithm>

#include "sim/random.hpp"

namespace msislab::sim {

Calibration calibration_of(const Scenario& scenario) {
  Calibration calibration;
  calibration.mru = scenario.mru.mount;
  // The compass deviation the simulated MRU has is the dataset's calibration, as the sonar's clock
  // offset is: the pipeline removes it as it would a calibrated real one.
  calibration.mru.deviation_cos_deg = scenario.mru.deviation_cos_deg;
  calibration.mru.deviation_sin_deg = scenario.mru.deviation_sin_deg;
  calibration.dvl = scenario.dvl.mount;
  calibration.sonar = scenario.sonar.mount;
  calibration.frame = scenario.gps.frame;
  return calibration;
}

namespace {
std::vector<RenderedBeam> render_beams(const Scenario& scenario, const Scene& scene,
                                       const VehicleTrajectory& truth, int threads) {
  const MsisModel model(scene, scenario.sonar, scenario.vehicle.depth_m);
  const double stop_s = scenario.sonar.stop_s
                            ? std::min(truth.end_s(), truth.start_s() + *scenario.sonar.stop_s)
                            : truth.end_s();
  const std::vector<BeamSlot> slots = beam_schedule(scenario.sonar, truth.start_s(), stop_s);
  std::vector<RenderedBeam> beams(slots.size());
  // TBB (Embree's own task scheduler) spreads the beams over `threads` threads; each beam owns
  // its slot in the output and its random stream, so the bytes do not depend on which thread
  // renders it.
  tbb::task_arena arena(threads);
  arena.execute([&] {
    tbb::parallel_for(std::size_t{0}, slots.size(), [&](std::size_t i) {
      Rng rng = make_rng(scenario.seed, RandomStream::kSonarBeam, slots[i].index);
      beams[i] = model.render(slots[i], truth, rng);
    });
  });
  return beams;
}
}  // namespace

SimulationResult simulate(const Scenario& scenario, const Scene& scene, int threads) {
  VehicleTrajectory truth = follow_path(scenario.vehicle);
  std::vector<RenderedBeam> beams = render_beams(scenario, scene, truth, std::max(threads, 1));
  std::vector<DvlSample> dvl =
      simulate_dvl(truth, scenario.dvl, scene, scenario.vehicle.depth_m, scenario.seed);
  std::vector<MruSample> mru = simulate_mru(truth, scenario.mru, scenario.seed);
  std::vector<GpsFix> gps = simulate_gps(truth, scenario.gps, scenario.seed);
  return {std::move(truth), std::move(beams), std::move(dvl), std::move(mru), std::move(gps)};
}

}  // namespace msislab::sim
