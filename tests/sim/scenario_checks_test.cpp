// sim/scenario_checks on a 60 x 30 m basin with one pier: a path through a wall or below the floor
// is an error naming the waypoint or the depth; a pass through the pier, a wall too close and a low
// altitude are warnings; segments past the run's end are errors or warnings by how much they miss.
#include "sim/scenario_checks.hpp"

#include <gtest/gtest.h>

#include "sim/scene_builder.hpp"

namespace msislab::sim {
namespace {

/// The basin: x 0..60, y 0..30, floor at -4 m, walls to +1 m; the pier a closed box x 28..32 from
/// the north wall (y 30) to y 20, floor to +1 m; a moored hull floating from +0.5 m down to -1 m
/// at x 10..14, y 20..24; a submerged crate from -3.5 m to -0.5 m at x 45..50, y 20..25.
TriangleMesh basin_with_pier() {
  MeshBuilder b;
  const auto walls = b.group("walls", 0.5f, 0.05f);
  const auto bottom = b.group("bottom", 0.003f, 0.3f);
  const auto pier = b.group("pier", 0.5f, 0.05f);
  const auto hull = b.group("hull", 0.5f, 0.05f);
  const auto crate = b.group("crate", 0.5f, 0.05f);
  add_basin(b, {{{0, 0}, {60, 0}, {60, 30}, {0, 30}}, {true, true, true, true}}, {1.0, -4.0, 0.0},
            walls, bottom);
  add_prism(b, {{28, 20}, {32, 20}, {32, 29.9}, {28, 29.9}}, -4.0, 1.0, pier);
  add_prism(b, {{10, 20}, {14, 20}, {14, 24}, {10, 24}}, -1.0, 0.5, hull);
  add_prism(b, {{45, 20}, {50, 20}, {50, 25}, {45, 25}}, -3.5, -0.5, crate);
  return b.mesh();
}

struct Checked {
  std::vector<ScenarioFinding> findings;

  const ScenarioFinding* first_error() const {
    for (const ScenarioFinding& f : findings) {
      if (f.error) return &f;
    }
    return nullptr;
  }
  std::size_t warnings() const {
    std::size_t n = 0;
    for (const ScenarioFinding& f : findings) n += f.error ? 0 : 1;
    return n;
  }
  std::string all() const {
    std::string text;
    for (const ScenarioFinding& f : findings)
      text += (f.error ? "error: " : "warning: ") + f.what + "\n";
    return text;
  }
};

Checked check(const std::vector<Eigen::Vector2d>& path, double depth_m = 1.5) {
  static const TriangleMesh mesh = basin_with_pier();
  static const Scene scene(mesh, Material{"water_surface", 0.001f, 0.9f});
  VehicleConfig vehicle;
  vehicle.depth_m = depth_m;
  vehicle.path_m = path;
  return {check_path(vehicle, scene)};
}

bool has(const std::string& text, const std::string& part) {
  return text.find(part) != std::string::npos;
}

TEST(ScenarioChecks, APathInOpenWaterPasses) {
  const Checked c = check({{5, 5}, {55, 5}, {55, 15}, {5, 15}});
  EXPECT_TRUE(c.findings.empty()) << c.all();
}

TEST(ScenarioChecks, AWaypointBehindAWallIsAnErrorAtThatWaypoint) {
  const Checked c = check({{5, 5}, {30, 10}, {70, 10}, {50, 5}});
  const ScenarioFinding* e = c.first_error();
  ASSERT_NE(e, nullptr) << c.all();
  EXPECT_EQ(e->key, ScenarioKey::kWaypoint);
  EXPECT_EQ(e->index, 2u) << "the leg's end, the waypoint behind the wall";
  EXPECT_TRUE(has(e->what, "waypoint 3 (70.0, 10.0)")) << e->what;
  EXPECT_TRUE(has(e->what, "crosses the mesh (group 'walls') at (60.0, 10.0)")) << e->what;
  EXPECT_TRUE(has(e->what, "leaves the water")) << e->what;
}

TEST(ScenarioChecks, AFirstWaypointOutsideTheSceneIsAnErrorAtIt) {
  const Checked c = check({{-10, 5}, {20, 5}});
  const ScenarioFinding* e = c.first_error();
  ASSERT_NE(e, nullptr) << c.all();
  EXPECT_EQ(e->key, ScenarioKey::kWaypoint);
  EXPECT_EQ(e->index, 0u);
  EXPECT_TRUE(has(e->what, "waypoint 1 (-10.0, 5.0) has no floor under it")) << e->what;
}

TEST(ScenarioChecks, ADepthBelowTheFloorIsAnErrorAboutTheDepth) {
  const Checked c = check({{5, 5}, {55, 5}}, 4.5);
  const ScenarioFinding* e = c.first_error();
  ASSERT_NE(e, nullptr) << c.all();
  EXPECT_EQ(e->key, ScenarioKey::kDepth);
  EXPECT_TRUE(has(e->what, "4.5 m puts the vehicle under the mesh (group 'bottom' at 4.00 m"))
      << e->what;
  EXPECT_TRUE(has(e->what, "below the floor")) << e->what;
}

TEST(ScenarioChecks, PassingUnderAFloatingHullIsNoFinding) {
  // The St. Pere replica's vehicle passes under a moored hull as the real one did.
  const Checked c = check({{5, 22}, {12, 22}, {20, 22}});
  EXPECT_TRUE(c.findings.empty()) << c.all();
}

TEST(ScenarioChecks, AWaypointInsideASubmergedSolidIsAnError) {
  const Checked c = check({{40, 22}, {47, 22}});
  const ScenarioFinding* e = c.first_error();
  ASSERT_NE(e, nullptr) << c.all();
  EXPECT_EQ(e->key, ScenarioKey::kDepth);
  EXPECT_TRUE(has(e->what, "under the mesh (group 'crate' at 0.50 m depth)")) << e->what;
}

TEST(ScenarioChecks, ALowAltitudeIsAWarning) {
  const Checked c = check({{5, 5}, {55, 5}}, 3.7);
  ASSERT_EQ(c.first_error(), nullptr) << c.all();
  ASSERT_EQ(c.warnings(), 1u) << c.all();
  EXPECT_EQ(c.findings[0].key, ScenarioKey::kDepth);
  EXPECT_TRUE(has(c.findings[0].what, "0.30 m above the floor")) << c.findings[0].what;
}

TEST(ScenarioChecks, ALegThroughThePierAndOutIsAWarning) {
  const Checked c = check({{20, 25}, {40, 25}, {40, 10}});
  ASSERT_EQ(c.first_error(), nullptr) << c.all();
  ASSERT_EQ(c.warnings(), 1u) << c.all();
  const ScenarioFinding& w = c.findings[0];
  EXPECT_EQ(w.index, 1u);
  EXPECT_TRUE(has(w.what, "runs 4.00 m through the mesh (group 'pier') at (28.0, 25.0)")) << w.what;
}

TEST(ScenarioChecks, ALegCloserToAWallThanTheClearanceIsAWarning) {
  const Checked c = check({{5, 0.6}, {20, 0.6}});
  ASSERT_EQ(c.first_error(), nullptr) << c.all();
  ASSERT_EQ(c.warnings(), 1u) << c.all();
  EXPECT_EQ(c.findings[0].index, 1u);
  EXPECT_TRUE(has(c.findings[0].what, "passes 0.60 m from the mesh (group 'walls')"))
      << c.findings[0].what;
}

TEST(ScenarioChecks, SegmentsPastTheEnd) {
  const std::vector<ScenarioFinding> f = check_segments(
      {{"early", 0, 50}, {"to_the_end", 60, 110}, {"mostly_after", 80, 200}, {"after", 100, 150}},
      100.0);
  ASSERT_EQ(f.size(), 2u);
  EXPECT_EQ(f[0].index, 2u);
  EXPECT_FALSE(f[0].error) << "less than half scored: a warning";
  EXPECT_TRUE(has(f[0].what, "less than half of it is scored (20 s of 120)")) << f[0].what;
  EXPECT_EQ(f[1].index, 3u);
  EXPECT_TRUE(f[1].error) << "nothing to score: an error";
  EXPECT_TRUE(has(f[1].what, "begins after the run, which lasts 100.0 s")) << f[1].what;
}

TEST(ScenarioChecks, CheckScenarioTimesTheSegmentsOnTheFollowedPath) {
  const TriangleMesh mesh = basin_with_pier();
  const Scene scene(mesh, Material{"water_surface", 0.001f, 0.9f});
  Scenario s;
  s.vehicle.path_m = {{5, 5}, {45, 5}};
  s.vehicle.speed_mps = 0.5;  // 40 m: about 80 s
  s.segments = {{"first", 0, 40}, {"late", 85, 120}};
  const std::vector<ScenarioFinding> f = check_scenario(s, scene);
  ASSERT_EQ(f.size(), 1u);
  EXPECT_EQ(f[0].key, ScenarioKey::kSegment);
  EXPECT_EQ(f[0].index, 1u);
  EXPECT_TRUE(f[0].error);
}

}  // namespace
}  // namespace msislab::sim
