// The scenario checks on the command line (docs/scenes.md, "Scenario checks"): `msislab simulate`
// and `msislab montecarlo` refuse a scenario whose path leaves the water, whose depth lies below
// the floor or whose key is misspelt, with exit 2 and one line naming the scenario file and line,
// before anything is written; warnings go to stderr and the command goes on.
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <string>

#include "cli_runner.hpp"
#include "test_support.hpp"

namespace msislab::app {
namespace {

namespace fs = std::filesystem;
using testing::CliResult;
using testing::run_msislab;
using testing::shell_quote;
using testing::TempDir;
using testing::write_text;

const std::string kHarbour = std::string(MSISLAB_SOURCE_DIR) + "/scenes/harbour.obj";

// The harbour (x -60..60, y -40..40, floor at -6 m) with small_basin's materials; `vehicle` is the
// text from line 7 on.
std::string harbour_scenario(const std::string& vehicle) {
  return "seed: 1\n"  // 1
         "scene:\n"   // 2
         "  mesh: " +
         kHarbour +
         "\n"                                                         // 3
         "  groups: {bottom: {backscatter: 0.003, specular: 0.3}}\n"  // 4
         "sonar: {rays_horizontal: 1, rays_vertical: 1, bins: 10}\n"  // 5
         "vehicle:\n"                                                 // 6
         + vehicle;
}

void expect_one_line(const CliResult& r, const std::string& start, const std::string& part) {
  EXPECT_EQ(r.exit_code, 2) << r.err;
  EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
  EXPECT_EQ(r.err.rfind("msislab: " + start, 0), 0u) << r.err << "\nexpected " << start;
  EXPECT_NE(r.err.find(part), std::string::npos) << r.err << "\nexpected " << part;
}

TEST(ScenarioChecksCli, SimulateRefusesAWaypointBehindAWall) {
  const TempDir tmp;
  const std::string scenario =
      write_text(tmp.file("s.yaml"), harbour_scenario("  depth_m: 2\n"       // 7
                                                      "  speed_mps: 0.5\n"   // 8
                                                      "  path:\n"            // 9
                                                      "    - [-5, -5]\n"     // 10
                                                      "    - [10, -5]\n"     // 11
                                                      "    - [70, -5]\n"));  // 12
  const CliResult r = run_msislab(
      "simulate " + shell_quote(scenario) + " --out " + shell_quote(tmp.file("out")), tmp);
  expect_one_line(r, scenario + ":12: key 'vehicle.path': the leg from waypoint 2",
                  "crosses the mesh (group 'walls') at (60.0, -5.0), 2.0 m deep, and leaves the "
                  "water");
  EXPECT_FALSE(fs::exists(tmp.path() / "out"));
}

TEST(ScenarioChecksCli, SimulateNamesAMisspeltRequiredKey) {
  const TempDir tmp;
  const std::string scenario =
      write_text(tmp.file("s.yaml"), harbour_scenario("  depth_m: 2\n"
                                                      "  sped_mps: 0.5\n"
                                                      "  path: [[-5, -5], [10, -5]]\n"));
  const CliResult r = run_msislab(
      "simulate " + shell_quote(scenario) + " --out " + shell_quote(tmp.file("out")), tmp);
  expect_one_line(
      r, scenario + ":8: key 'vehicle.sped_mps': ", "unknown key (did you mean 'speed_mps'?)");
}

TEST(ScenarioChecksCli, MontecarloRefusesADepthBelowTheFloorBeforeAnyRun) {
  const TempDir tmp;
  const std::string scenario =
      write_text(tmp.file("s.yaml"), harbour_scenario("  depth_m: 6.5\n"
                                                      "  speed_mps: 0.5\n"
                                                      "  path: [[-5, -5], [10, -5]]\n"));
  const CliResult r =
      run_msislab("montecarlo " + shell_quote(scenario) +
                      " --runs 2 --methods deadreckoning --out " + shell_quote(tmp.file("mc")),
                  tmp);
  expect_one_line(r, scenario + ":7: key 'vehicle.depth_m': 6.5 m puts the vehicle under the mesh",
                  "below the floor");
  EXPECT_FALSE(fs::exists(tmp.path() / "mc"));
}

TEST(ScenarioChecksCli, AWarningGoesToStderrAndTheRunGoesOn) {
  const TempDir tmp;
  // 0.37 m from a piling of the pier (x = 18, y = 8): closer than the 1 m clearance.
  const std::string scenario =
      write_text(tmp.file("s.yaml"), harbour_scenario("  depth_m: 2\n"
                                                      "  speed_mps: 0.5\n"
                                                      "  path: [[-5, -5], [10, -5], [20, 10]]\n"));
  const CliResult r = run_msislab(
      "simulate " + shell_quote(scenario) + " --out " + shell_quote(tmp.file("out")), tmp);
  EXPECT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(r.err.rfind("msislab: " + scenario + ":9: warning: key 'vehicle.path': ", 0), 0u)
      << r.err;
  EXPECT_NE(r.err.find("passes 0.37 m from the mesh (group 'pilings')"), std::string::npos)
      << r.err;
  EXPECT_TRUE(fs::is_directory(tmp.path() / "out"));
}

}  // namespace
}  // namespace msislab::app
