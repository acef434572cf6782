#include "sim/simulator.hpp"

#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

#include <algorithm>
#include <stdexcept>

#include "sim/random.hpp"

namespace msislab::sim {

Calibration true_calibration(const Scenario& scenario) {
  Calibration calibration;
  calibration.mru = scenario.mru.mount;
  // The compass deviation the simulated MRU has is the dataset's calibration, as the sonar's clock
  // offset is: the pipeline removes it as it would a calibrated real one.
  calibration.mru.deviation_cos_deg = scenario.mru.deviation_cos_deg;
  calibration.mru.deviation_sin_deg = scenario.mru.deviation_sin_deg;
  calibration.dvl = scenario.dvl.mount;
  calibration.dvl.scale_factor = scenario.dvl.scale_factor;
  calibration.sonar = scenario.sonar.mount;
  // Ranges come out sound_speed / water_sound_speed times the true ones.
  calibration.sonar.range_scale =
      scenario.sonar.sound_speed_mps /
      scenario.sonar.water_sound_speed_mps.value_or(scenario.sonar.sound_speed_mps);
  calibration.frame = scenario.gps.frame;
  return calibration;
}

Calibration calibration_of(const Scenario& scenario) {
  return scenario.stated_calibration ? *scenario.stated_calibration : true_calibration(scenario);
}

namespace {

/// The scenario's beams, up to the sonar's stop time.
std::vector<BeamSlot> beam_slots(const Scenario& scenario, const VehicleTrajectory& truth) {
  const double stop_s = scenario.sonar.stop_s
                            ? std::min(truth.end_s(), truth.start_s() + *scenario.sonar.stop_s)
                            : truth.end_s();
  return beam_schedule(scenario.sonar, truth.start_s(), stop_s);
}

/// The random stream of a beam's speckle and noise.
Rng beam_rng(const Scenario& scenario, const BeamSlot& slot) {
  return make_rng(scenario.seed, RandomStream::kSonarBeam, slot.index);
}

/// f(i) for every beam i over `threads` threads. TBB (Embree's own task scheduler) spreads the
/// beams; each beam owns its slot in the output and its random stream, so the bytes do not
/// depend on which thread does it.
template <typename PerBeam>
void for_each_beam(std::size_t count, int threads, const PerBeam& f) {
  tbb::task_arena arena(std::max(threads, 1));
  arena.execute([&] { tbb::parallel_for(std::size_t{0}, count, f); });
}

SimulationResult with_navigation(const Scenario& scenario,
                                 const std::vector<double>& dvl_altitude_m, VehicleTrajectory truth,
                                 std::vector<RenderedBeam> beams) {
  std::vector<DvlSample> dvl = simulate_dvl(truth, scenario.dvl, dvl_altitude_m, scenario.seed);
  std::vector<MruSample> mru = simulate_mru(truth, scenario.mru, scenario.seed);
  std::vector<GpsFix> gps = simulate_gps(truth, scenario.gps, scenario.seed);
  return {std::move(truth), std::move(beams), std::move(dvl), std::move(mru), std::move(gps)};
}

}  // namespace

SimulationResult simulate(const Scenario& scenario, const Scene& scene, int threads) {
  VehicleTrajectory truth = follow_path(scenario.vehicle);
  const MsisModel model(scene, scenario.sonar, scenario.vehicle.depth_m);
  const std::vector<BeamSlot> slots = beam_slots(scenario, truth);
  std::vector<RenderedBeam> beams(slots.size());
  for_each_beam(slots.size(), threads, [&](std::size_t i) {
    Rng rng = beam_rng(scenario, slots[i]);
    beams[i] = model.render(slots[i], truth, rng);
  });
  const std::vector<double> altitudes_m =
      dvl_altitudes(truth, scenario.dvl, scene, scenario.vehicle.depth_m);
  return with_navigation(scenario, altitudes_m, std::move(truth), std::move(beams));
}

ScenarioTrace trace_scenario(const Scenario& scenario, const Scene& scene, int threads) {
  const VehicleTrajectory truth = follow_path(scenario.vehicle);
  const MsisModel model(scene, scenario.sonar, scenario.vehicle.depth_m);
  const std::vector<BeamSlot> slots = beam_slots(scenario, truth);
  ScenarioTrace trace;
  trace.beams.resize(slots.size());
  for_each_beam(slots.size(), threads,
                [&](std::size_t i) { trace.beams[i] = model.trace(slots[i], truth); });
  trace.dvl_altitude_m = dvl_altitudes(truth, scenario.dvl, scene, scenario.vehicle.depth_m);
  return trace;
}

SimulationResult simulate(const Scenario& scenario, const ScenarioTrace& trace, int threads) {
  VehicleTrajectory truth = follow_path(scenario.vehicle);
  const MsisReceiver receiver = MsisModel::receiver_of(scenario.sonar);
  const std::vector<BeamSlot> slots = beam_slots(scenario, truth);
  const auto same_slot = [](const BeamSlot& a, const BeamEchoes& b) {
    return a.index == b.slot.index && a.t_s == b.slot.t_s &&
           a.transducer_angle_rad == b.slot.transducer_angle_rad;
  };
  if (!std::equal(slots.begin(), slots.end(), trace.beams.begin(), trace.beams.end(), same_slot)) {
    throw std::invalid_argument("simulate: the traced echoes are not this scenario's beams");
  }
  std::vector<RenderedBeam> beams(slots.size());
  for_each_beam(slots.size(), threads, [&](std::size_t i) {
    Rng rng = beam_rng(scenario, slots[i]);
    beams[i] = receive_beam(receiver, trace.beams[i], rng);
  });
  return with_navigation(scenario, trace.dvl_altitude_m, std::move(truth), std::move(beams));
}

}  // namespace msislab::sim
