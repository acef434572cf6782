// The whole simulation: the scenario's rays (the sonar's echoes, the DVL's altitudes) traced once
// and shared by runs of other seeds give the bytes each run would have traced for itself, for any
// thread count, and are refused for another scenario's beams or DVL samples.
#include "sim/simulator.hpp"

#include <gtest/gtest.h>

#include <stdexcept>

namespace msislab::sim {
namespace {

/// A 60 m square basin with walls from the bottom (z = -10) to above the surface.
TriangleMesh basin_mesh() {
  TriangleMesh mesh;
  const float h = 30.0f;
  mesh.vertices_m = {{-h, -h, -10}, {h, -h, -10}, {h, h, -10}, {-h, h, -10},
                     {-h, -h, 1},   {h, -h, 1},   {h, h, 1},   {-h, h, 1}};
  mesh.triangles = {{0, 1, 2}, {0, 2, 3},                        // bottom
                    {0, 4, 5}, {0, 5, 1}, {1, 5, 6}, {1, 6, 2},  // walls
                    {2, 6, 7}, {2, 7, 3}, {3, 7, 4}, {3, 4, 0}};
  mesh.material_ids = {1, 1, 0, 0, 0, 0, 0, 0, 0, 0};
  mesh.materials = {Material{"wall", 0.5f, 0.05f}, Material{"bottom", 0.05f, 0.0f}};
  mesh.group_names = {"wall", "bottom"};
  return mesh;
}

Scenario basin_scenario(std::uint64_t seed) {
  Scenario scenario;
  scenario.seed = seed;
  scenario.vehicle.speed_mps = 0.5;
  scenario.vehicle.path_m = {{-10.0, -10.0}, {10.0, -10.0}, {10.0, 5.0}};
  scenario.sonar.stop_s = 20.0;  // about 290 beams
  return scenario;
}

void expect_same_beams(const SimulationResult& a, const SimulationResult& b) {
  ASSERT_EQ(a.beams.size(), b.beams.size());
  for (std::size_t i = 0; i < a.beams.size(); ++i) {
    EXPECT_EQ(a.beams[i].intensity, b.beams[i].intensity) << "beam " << i;
    EXPECT_EQ(a.beams[i].rays_cast, b.beams[i].rays_cast) << "beam " << i;
    EXPECT_EQ(a.beams[i].slot.t_s, b.beams[i].slot.t_s) << "beam " << i;
    EXPECT_EQ(a.beams[i].truth.strongest_range_m, b.beams[i].truth.strongest_range_m);
    EXPECT_EQ(a.beams[i].truth.strongest_surface, b.beams[i].truth.strongest_surface);
    EXPECT_EQ(a.beams[i].truth.first_hit_range_m, b.beams[i].truth.first_hit_range_m);
  }
  ASSERT_EQ(a.dvl.size(), b.dvl.size());
  for (std::size_t i = 0; i < a.dvl.size(); ++i) {
    EXPECT_EQ(a.dvl[i].t_s, b.dvl[i].t_s);
    EXPECT_EQ(a.dvl[i].altitude_m, b.dvl[i].altitude_m);
    EXPECT_EQ(a.dvl[i].bottom_lock, b.dvl[i].bottom_lock);
    EXPECT_EQ(a.dvl[i].v_dvl_mps, b.dvl[i].v_dvl_mps);
  }
}

TEST(Simulator, SharedEchoesGiveEachSeedTheBeamsItWouldHaveTraced) {
  const TriangleMesh mesh = basin_mesh();
  const Scene scene(mesh, Material{"surface", 0.001f, 0.9f});
  const ScenarioTrace trace = trace_scenario(basin_scenario(1), scene, 2);
  ASSERT_GT(trace.beams.size(), 200u);
  for (const std::uint64_t seed : {1u, 2u}) {
    const Scenario scenario = basin_scenario(seed);
    const SimulationResult traced = simulate(scenario, scene, 1);
    expect_same_beams(traced, simulate(scenario, trace, 1));
    expect_same_beams(traced, simulate(scenario, trace, 2));
  }
  // And the seeds differ where they should: speckle and noise.
  const SimulationResult one = simulate(basin_scenario(1), trace, 1);
  const SimulationResult two = simulate(basin_scenario(2), trace, 1);
  int differing = 0;
  for (std::size_t i = 0; i < one.beams.size(); ++i) {
    differing += one.beams[i].intensity != two.beams[i].intensity ? 1 : 0;
  }
  EXPECT_GT(differing, static_cast<int>(one.beams.size()) / 2);
}

TEST(Simulator, EchoesOfAnotherScenarioAreRefused) {
  const TriangleMesh mesh = basin_mesh();
  const Scene scene(mesh, Material{"surface", 0.001f, 0.9f});
  const ScenarioTrace trace = trace_scenario(basin_scenario(1), scene, 1);
  Scenario shorter = basin_scenario(1);
  shorter.sonar.stop_s = 10.0;
  EXPECT_THROW(simulate(shorter, trace, 1), std::invalid_argument);
  Scenario slower = basin_scenario(1);
  slower.sonar.revolution_s = 14.0;
  EXPECT_THROW(simulate(slower, trace, 1), std::invalid_argument);
  Scenario dvl_faster = basin_scenario(1);
  dvl_faster.dvl.rate_hz *= 2.0;
  EXPECT_THROW(simulate(dvl_faster, trace, 1), std::invalid_argument);
}

}  // namespace
}  // namespace msislab::sim
