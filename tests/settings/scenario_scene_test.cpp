// io/scenario_scene: a scenario read with its mesh and checked. Each check's message starts with
// the scenario file and the line of the waypoint, key or segment concerned; a wrong mesh path
// names that line and where it led; a mesh of one group gets a mud floor and concrete walls; a
// floor as bright as the walls is a warning.
#include "settings/scenario_scene.hpp"

#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <filesystem>
#include <string>

#include "io/input_error.hpp"
#include "io/mesh_io.hpp"
#include "sim/scene_builder.hpp"
#include "test_support.hpp"

namespace msislab::settings {
namespace {

namespace fs = std::filesystem;
using testing::TempDir;
using testing::write_text;

// A 60 x 30 m basin (floor at -4 m) with a pier x 28..32 from the north wall to y = 20, all in one
// group named `group` ("" writes no `g` line).
void write_basin(const std::string& path, const std::string& group) {
  sim::MeshBuilder b;
  const auto g = b.group(group, 0.5f, 0.3f);
  sim::add_basin(b, {{{0, 0}, {60, 0}, {60, 30}, {0, 30}}, {true, true, true, true}},
                 {1.0, -4.0, 0.0}, g, g);
  sim::add_prism(b, {{28, 20}, {32, 20}, {32, 29.9}, {28, 29.9}}, -4.0, 1.0, g);
  io::write_obj(path, b.mesh());
}

// Line numbers below refer to this layout.
std::string scenario(const std::string& vehicle_lines, const std::string& rest = "") {
  return "seed: 1\n"            // 1
         "scene:\n"             // 2
         "  mesh: basin.obj\n"  // 3
         "vehicle:\n"           // 4
         "  depth_m: 1.5\n"     // 5
         "  speed_mps: 0.5\n"   // 6
         "  path:\n"            // 7
         + vehicle_lines + rest;
}

const std::string kGoodPath =
    "    - [5, 5]\n"     // 8
    "    - [50, 5]\n"    // 9
    "    - [50, 15]\n";  // 10

struct Basin {
  TempDir dir;
  std::string path;
  explicit Basin(const std::string& text, const std::string& group = "basin") {
    write_basin(dir.file("basin.obj"), group);
    path = write_text(dir.file("scenario.yaml"), text);
  }
  std::string error() const {
    try {
      read_checked_scenario(path);
    } catch (const io::InputError& e) {
      return e.what();
    }
    ADD_FAILURE() << "no InputError for " << path;
    return "";
  }
};

bool starts_with(const std::string& text, const std::string& start) {
  return text.rfind(start, 0) == 0;
}
bool has(const std::string& text, const std::string& part) {
  return text.find(part) != std::string::npos;
}

TEST(ScenarioScene, AGoodScenarioPassesWithoutWarnings) {
  const Basin basin(scenario(kGoodPath));
  const CheckedScenario checked = read_checked_scenario(basin.path);
  EXPECT_TRUE(checked.warnings.empty()) << checked.warnings.front();
  EXPECT_FALSE(checked.mesh.triangles.empty());
}

TEST(ScenarioScene, AWaypointThroughAWallIsAnErrorAtItsLine) {
  const Basin basin(scenario("    - [5, 5]\n    - [30, 10]\n    - [70, 10]\n    - [50, 5]\n"));
  const std::string e = basin.error();
  EXPECT_TRUE(starts_with(e, basin.path + ":10: key 'vehicle.path': the leg from waypoint 2")) << e;
  EXPECT_TRUE(has(e, "crosses the mesh (group 'basin') at (60.0, 10.0)")) << e;
}

TEST(ScenarioScene, ADepthBelowTheFloorIsAnErrorAtTheDepthLine) {
  Basin basin(scenario(kGoodPath));
  write_text(basin.path, scenario(kGoodPath).replace(scenario(kGoodPath).find("1.5"), 3, "4.5"));
  const std::string e = basin.error();
  EXPECT_TRUE(starts_with(e, basin.path + ":5: key 'vehicle.depth_m': 4.5 m puts the vehicle"))
      << e;
}

TEST(ScenarioScene, ASegmentAfterTheRunIsAnErrorAtItsLine) {
  const Basin basin(scenario(kGoodPath, "segments:\n  start: [0, 30]\n  late: [500, 600]\n"));
  const std::string e = basin.error();
  EXPECT_TRUE(starts_with(e, basin.path + ":13: key 'segments.late': [500, 600] s begins after"))
      << e;
}

TEST(ScenarioScene, ASegmentMostlyAfterTheRunIsAWarningAtItsLine) {
  const Basin basin(scenario(kGoodPath, "segments: {start: [0, 30], long: [60, 400]}\n"));
  const CheckedScenario checked = read_checked_scenario(basin.path);
  ASSERT_EQ(checked.warnings.size(), 1u);
  EXPECT_TRUE(starts_with(checked.warnings[0], basin.path + ":11: warning: key 'segments.long'"))
      << checked.warnings[0];
  const Basin quiet(scenario(kGoodPath,
                             "segments: {start: [0, 30], long: [60, 400]}\n"
                             "quiet_warnings: [segment_after_run]\n"));
  EXPECT_TRUE(read_checked_scenario(quiet.path).warnings.empty());
}

TEST(ScenarioScene, AWrongMeshPathNamesTheScenarioLineAndTheResolvedPath) {
  Basin basin(scenario(kGoodPath));
  write_text(basin.path, "seed: 1\nscene:\n  groups: {}\n  mesh: ../scenes/basin.obj\n" +
                             scenario(kGoodPath).substr(scenario(kGoodPath).find("vehicle:")));
  const std::string e = basin.error();
  const std::string resolved = (basin.dir.path().parent_path() / "scenes" / "basin.obj").string();
  EXPECT_TRUE(starts_with(e, basin.path + ":4: key 'scene.mesh': '../scenes/basin.obj'")) << e;
  EXPECT_TRUE(has(e, resolved + ", which does not exist")) << e << "\nexpected " << resolved;
}

TEST(ScenarioScene, AMeshOfOneGroupGetsAMudFloorAndConcreteWalls) {
  for (const std::string group : {"", "basin"}) {
    SCOPED_TRACE("group '" + group + "'");
    const Basin basin(scenario(kGoodPath), group);
    const CheckedScenario checked = read_checked_scenario(basin.path);
    EXPECT_TRUE(checked.warnings.empty());
    const sim::TriangleMesh& mesh = checked.mesh;
    double floor_m2 = 0.0;
    for (std::size_t i = 0; i < mesh.triangles.size(); ++i) {
      const sim::Material& m = mesh.materials[mesh.material_ids[i]];
      const Eigen::Vector3i& t = mesh.triangles[i];
      const bool on_floor = mesh.vertices_m[t[0]].z() == -4.0f &&
                            mesh.vertices_m[t[1]].z() == -4.0f &&
                            mesh.vertices_m[t[2]].z() == -4.0f;
      EXPECT_EQ(m.backscatter, on_floor ? 0.003f : 0.5f) << "triangle " << i;
      EXPECT_EQ(m.specular, on_floor ? 0.3f : 0.05f) << "triangle " << i;
      const Eigen::Vector3f a = mesh.vertices_m[t[0]], b = mesh.vertices_m[t[1]];
      if (on_floor) floor_m2 += 0.5 * (b - a).cross(mesh.vertices_m[t[2]] - a).norm();
    }
    EXPECT_NEAR(floor_m2, 60.0 * 30.0 + 4.0 * 9.9, 0.01) << "the floor and the pier's foot";
  }
}

TEST(ScenarioScene, AFloorAsBrightAsTheWallsIsAWarningUnlessTheAuthorGaveIt) {
  {
    // The floor's material written out is what the author means: no warning.
    const Basin basin("seed: 1\nscene:\n  mesh: basin.obj\n  bottom: {backscatter: 0.5}\n" +
                      scenario(kGoodPath).substr(scenario(kGoodPath).find("vehicle:")));
    EXPECT_TRUE(read_checked_scenario(basin.path).warnings.empty());
  }
  {
    const Basin basin(scenario(kGoodPath).replace(scenario(kGoodPath).find("vehicle:"), 0,
                                                  "  groups: {basin: {backscatter: 0.5}}\n"));
    const CheckedScenario checked = read_checked_scenario(basin.path);
    ASSERT_EQ(checked.warnings.size(), 1u);
    EXPECT_TRUE(starts_with(checked.warnings[0], basin.path + ":2: warning: key 'scene': "))
        << checked.warnings[0];
    // Silenced by name.
    const Basin quiet(scenario(kGoodPath).replace(scenario(kGoodPath).find("vehicle:"), 0,
                                                  "  groups: {basin: {backscatter: 0.5}}\n") +
                      "quiet_warnings: [bright_floor]\n");
    EXPECT_TRUE(read_checked_scenario(quiet.path).warnings.empty());
  }
}

TEST(ScenarioScene, QuietWarningsNamesOnlyKnownWarnings) {
  const Basin basin(scenario(kGoodPath) + "quiet_warnings: [bright_flor]\n");
  try {
    read_checked_scenario(basin.path);
    ADD_FAILURE() << "no InputError";
  } catch (const io::InputError& e) {
    EXPECT_NE(std::string(e.what()).find("key 'quiet_warnings': unknown warning 'bright_flor' "
                                         "(did you mean 'bright_floor'?); known: through_object, "
                                         "wall_clearance, bottom_clearance, segment_after_run, "
                                         "bright_floor"),
              std::string::npos)
        << e.what();
  }
}

}  // namespace
}  // namespace msislab::settings
