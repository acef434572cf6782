// The scenarios and scenes shipped in scenarios/ and scenes/: each passes the scenario checks;
// stpere_replica simulates end to end, reads back through the I/O module, and its sonar agrees
// with the truth (the simulator's acceptance figures).
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <sstream>

#include "app/run_command.hpp"
#include "app/simulate_command.hpp"
#include "dataset/dataset.hpp"
#include "io/input_error.hpp"
#include "io/stpere_logs.hpp"
#include "settings/scenario_scene.hpp"
#include "settings/scenario_yaml.hpp"
#include "sim/scene.hpp"
#include "test_support.hpp"

namespace msislab::app {
namespace {

namespace fs = std::filesystem;

const fs::path kScenarios = fs::path(MSISLAB_SOURCE_DIR) / "scenarios";

// Every shipped scenario passes the scenario checks (docs/scenes.md): no error, and no warning but
// the replica's, whose real track clips a traced clutter object (docs/scenes.md, stpere_replica).
TEST(ShippedScenarios, EveryScenarioPassesTheChecksAndItsSceneBuilds) {
  int count = 0;
  for (const auto& entry : fs::directory_iterator(kScenarios)) {
    if (entry.path().extension() != ".yaml") continue;
    SCOPED_TRACE(entry.path().string());
    settings::CheckedScenario checked;
    try {
      checked = settings::read_checked_scenario(entry.path().string());
    } catch (const io::InputError& e) {
      ADD_FAILURE() << e.what();
      continue;
    }
    for (const std::string& warning : checked.warnings) {
      const bool known = entry.path().filename() == "stpere_replica.yaml" &&
                         warning.find("(group 'clutter')") != std::string::npos;
      EXPECT_TRUE(known) << warning;
    }
    const sim::Scene scene(checked.mesh, checked.scenario.scene.surface);
    // A scenario that names its scene's groups uses no default material; basin_pier, which
    // names none, gets a mud floor and concrete walls.
    for (const sim::Material& m : checked.mesh.materials) {
      if (checked.scenario.scene.group_materials.empty()) {
        EXPECT_TRUE(m.name == "bottom" ? m.backscatter == 0.003f : m.backscatter == 0.5f) << m.name;
      } else {
        EXPECT_EQ(checked.scenario.scene.group_materials.count(m.name), 1u) << m.name;
      }
    }
    ++count;
  }
  EXPECT_GE(count, 6);
}

struct BeamAgreement {
  int with_hit = 0;
  int within_1_5_m = 0;
  int multipath = 0;
  int other_surface = 0;  ///< direct, but from another surface than the walls (the bottom)
};

BeamAgreement agreement(const std::string& beams_csv) {
  std::ifstream in(beams_csv);
  std::string line;
  std::getline(in, line);  // header
  BeamAgreement a;
  while (std::getline(in, line)) {
    std::vector<std::string> f;
    std::stringstream row(line);
    for (std::string cell; std::getline(row, cell, ',');) f.push_back(cell);
    if (f.size() < 9 || f[5].empty()) continue;
    ++a.with_hit;
    if (!f[6].empty() && std::abs(std::stod(f[6]) - std::stod(f[5])) <= 1.5) {
      ++a.within_1_5_m;
    } else if (f[7] == "1") {
      ++a.multipath;
    } else if (f[8] != "walls") {
      ++a.other_surface;
    }
  }
  return a;
}

TEST(ShippedScenarios, StPereReplicaSimulatesAndAgreesWithItsTruth) {
  testing::TempDir tmp;
  const std::string out = tmp.file("replica");
  const SimulateSummary summary =
      simulate({(kScenarios / "stpere_replica.yaml").string(), out, std::nullopt, 2});
  std::cout << "stpere_replica: " << summary.beams << " beams over " << summary.duration_s
            << " s simulated in " << summary.render_s << " s ("
            << summary.duration_s / summary.render_s << "x real time)\n";
  // 200 beams per 13.8 s until the sonar stops, 3020 s into the 3341 s run (where the real
  // sonar log ends, sonar.stop_s).
  const sim::Scenario scenario =
      settings::read_scenario((kScenarios / "stpere_replica.yaml").string());
  ASSERT_TRUE(scenario.sonar.stop_s);
  EXPECT_LT(*scenario.sonar.stop_s, summary.duration_s - 300.0);
  EXPECT_NEAR(static_cast<double>(summary.beams), *scenario.sonar.stop_s / 13.8 * 200.0, 2.0);
  const dataset::DatasetFiles files = dataset::find_dataset_files(out);
  ASSERT_TRUE(files.is_log && files.dvl && files.mti && files.gps && files.truth_beams);
  const auto beams = io::read_is_log(*files.is_log);
  EXPECT_EQ(beams.size(), summary.beams);
  EXPECT_EQ(beams.front().intensity.size(), 500u);

  const BeamAgreement a = agreement(*files.truth_beams);
  const double within = double(a.within_1_5_m) / a.with_hit;
  const double flagged = double(a.multipath) / a.with_hit;
  const double other = double(a.other_surface) / a.with_hit;
  std::cout << "beams seeing a surface: " << a.with_hit << ", strongest echo within 1.5 m of the "
            << "first hit: " << 100 * within << "%, multipath-flagged: " << 100 * flagged
            << "%, strongest echo from another surface (bottom): " << 100 * other << "%\n";
  EXPECT_GT(a.with_hit, static_cast<int>(summary.beams / 2));
  // Within 1.5 m, not 0.3 m as with point echoes: each ray is a surface patch whose echo
  // spreads over its ranges and the 0.375 m pulse, so an oblique wall's strongest bin lies up to
  // a metre or so beyond the axis's first hit (docs/simulator.md). Measured at seed 42: 84.4 %
  // within 1.5 m (92.4 % with the earlier 3 deg beam, 98.9 % within 0.3 m with point echoes).
  EXPECT_GE(within, 0.82);
  // The rest is explained by the truth: a multipath route, or the bottom outshining a far wall;
  // but for about 6 %, a nearer wall under the beam's +-15 deg (2.5 of its 6 deg beamwidths)
  // whose bright patch (10 dB roughness) outshines a dark or grazing one on the axis, which the
  // per-beam truth cannot name (tests/app/simulate_command_test.cpp checks that case against the
  // box's geometry). Measured: 93.3 % (97.3 % with the 3 deg beam; 99.5 % or more with point
  // echoes on even walls).
  EXPECT_GE(within + flagged + other, 0.92);

  // The pipeline reads it: dead reckoning against the simulation truth, drift of a few metres.
  const RunOutcome dr = run({out, "deadreckoning", tmp.file("dr"), ""});
  ASSERT_TRUE(dr.metrics);
  EXPECT_EQ(dr.metrics->truth, "simulation");
  EXPECT_LT(dr.metrics->errors.mean_m, 15.0);
}

}  // namespace
}  // namespace msislab::app
