// `msislab footprint` end to end on the marina loop: a table measured against the simulation's
// truth, written as a SLAM config that reads back, runs, and is the same bytes when measured
// again; the readings' offsets where the walls face the sonar as the footprint measurement gives
// them (docs/simulator.md); bad input refused with exit 2 and nothing written.
#include "app/footprint_command.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>

#include "app/simulate_command.hpp"
#include "cli_runner.hpp"
#include "io/input_error.hpp"
#include "settings/config_yaml.hpp"
#include "test_support.hpp"

namespace msislab::app {
namespace {

namespace fs = std::filesystem;

const fs::path kSourceDir(MSISLAB_SOURCE_DIR);

TEST(FootprintCommand, MeasuresATableThatRunsCarry) {
  testing::TempDir tmp;
  const std::string dataset = tmp.file("sim");
  simulate({(kSourceDir / "scenarios" / "marina_loop.yaml").string(), dataset, std::nullopt, 2});
  const std::string base = testing::write_text(
      tmp.file("base.yaml"), "# my front end\ntrajectory_slam: {iekf_iterations: 4}\n");
  FootprintOptions options;
  options.dataset_dirs = {dataset};
  options.out_path = tmp.file("footprint.yaml");
  options.config_path = base;
  const FootprintSummary s = measure_footprint_command(options);
  std::cout << s.cells_with_figure << " of " << s.cells << " cells from " << s.samples
            << " samples of " << s.readings << " readings (" << s.left_out << " left out)\n";
  EXPECT_EQ(s.datasets, 1u);
  EXPECT_EQ(s.cells, 10u * 6u);          // 5..50 m by 5, 0..75 deg by 15
  EXPECT_GT(s.samples, s.readings / 2);  // most readings of a harbour lie on its walls
  EXPECT_GE(s.cells_with_figure, 10u);

  const std::string text = testing::read_text(options.out_path);
  EXPECT_EQ(
      text.rfind("# A SLAM config with the beam's footprint, written by msislab footprint\n", 0),
      0u);
  EXPECT_NE(text.find("# my front end\ntrajectory_slam: {iekf_iterations: 4}\n"),
            std::string::npos);
  const SlamConfig config = settings::read_slam_config(options.out_path);
  EXPECT_EQ(config.trajectory_slam.front_end.iekf_iterations, 4);
  const FootprintTable& t = config.footprint.table;
  ASSERT_FALSE(t.empty());
  // Where the walls face the sonar (0 and 15 deg) at 10-20 m, the default sonar's strongest bin
  // lies beyond the wall: 0.32 m at 20 m and normal incidence on an ideal wall
  // (docs/simulator.md). Each cell averages hundreds of readings of spread 0.1-0.4 m (standard
  // error below 0.03 m); the bounds say "beyond, by a pulse's length", not a figure.
  int checked = 0;
  for (std::size_t i = 0; i < t.ranges_m.size(); ++i) {
    for (std::size_t j = 0; j < 2; ++j) {
      const double offset_m = t.offset_m[i * t.incidences_rad.size() + j];
      if (t.ranges_m[i] < 10.0 || t.ranges_m[i] > 20.0 || std::isnan(offset_m)) continue;
      EXPECT_GT(offset_m, 0.1) << t.ranges_m[i] << " m, cell " << j;
      EXPECT_LT(offset_m, 0.8) << t.ranges_m[i] << " m, cell " << j;
      ++checked;
    }
  }
  EXPECT_GE(checked, 2);

  // Measured again over its own output: the same bytes.
  measure_footprint_command(options);
  EXPECT_EQ(testing::read_text(options.out_path), text);
  // And a run takes it.
  const testing::CliResult run = testing::run_msislab(
      "run " + testing::shell_quote(dataset) + " --method robocentric --config " +
          testing::shell_quote(options.out_path) + " --out " +
          testing::shell_quote(tmp.file("run")),
      tmp);
  EXPECT_EQ(run.exit_code, 0) << run.err;
  EXPECT_TRUE(fs::is_regular_file(fs::path(tmp.file("run")) / "trajectory.tum"));
}

TEST(FootprintCommand, BadInputExitsTwoAndWritesNothing) {
  testing::TempDir tmp;
  const std::string dataset = tmp.file("sim");
  simulate({(kSourceDir / "scenarios" / "marina_loop.yaml").string(), dataset, std::nullopt, 2});
  const auto footprint = [&](const std::string& args) {
    return testing::run_msislab("footprint " + args, tmp);
  };
  // A file msislab did not write is kept.
  const std::string mine = testing::write_text(tmp.file("mine.yaml"), "my: notes\n");
  testing::CliResult r =
      footprint(testing::shell_quote(dataset) + " --out " + testing::shell_quote(mine));
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find(mine), std::string::npos) << r.err;
  EXPECT_EQ(testing::read_text(mine), "my: notes\n");
  // A dataset without its truth.
  const std::string bare = tmp.file("bare");
  fs::copy(dataset, bare, fs::copy_options::recursive);
  fs::remove(fs::path(bare) / "truth" / "beams.csv");
  const std::string out = tmp.file("out.yaml");
  r = footprint(testing::shell_quote(bare) + " --out " + testing::shell_quote(out));
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("truth/beams.csv"), std::string::npos) << r.err;
  // A base config that has a table already.
  ASSERT_EQ(
      footprint(testing::shell_quote(dataset) + " --out " + testing::shell_quote(out)).exit_code,
      0);
  r = footprint(testing::shell_quote(dataset) + " --config " + testing::shell_quote(out) +
                " --out " + testing::shell_quote(tmp.file("again.yaml")));
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("has a footprint section"), std::string::npos) << r.err;
  // Nor may it have a footprint section of any kind: the one written would be a second.
  const std::string lines =
      testing::write_text(tmp.file("lines.yaml"), "footprint: {line_radius_m: 2}\n");
  r = footprint(testing::shell_quote(dataset) + " --config " + testing::shell_quote(lines) +
                " --out " + testing::shell_quote(tmp.file("again.yaml")));
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("has a footprint section"), std::string::npos) << r.err;
  // A grid out of range, and a missing dataset.
  r = footprint(testing::shell_quote(dataset) + " --incidence-step 95 --out " +
                testing::shell_quote(tmp.file("g.yaml")));
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("--incidence-step"), std::string::npos) << r.err;
  r = footprint(testing::shell_quote(tmp.file("nothing")) + " --out " +
                testing::shell_quote(tmp.file("n.yaml")));
  EXPECT_EQ(r.exit_code, 2);
  for (const char* name : {"again.yaml", "g.yaml", "n.yaml"}) {
    EXPECT_FALSE(fs::exists(tmp.file(name))) << name;
  }
}

}  // namespace
}  // namespace msislab::app
