// `msislab sweep` end to end on small_basin: a 2x2 grid of a scenario key and a SLAM config key
// (2 runs per cell), sweep.csv, resuming, shards merged into the same bytes, a failed run's exit
// status, and bad input rejected before anything runs.
#include "app/sweep_command.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <sstream>
#include <string>

#include "cli_runner.hpp"
#include "io/input_error.hpp"
#include "results/sweep_files.hpp"
#include "settings/scenario_yaml.hpp"
#include "settings/sweep_yaml.hpp"
#include "test_support.hpp"

namespace msislab::app {
namespace {

namespace fs = std::filesystem;
using testing::read_text;
using testing::TempDir;
using testing::write_text;

const std::string kScenario = std::string(MSISLAB_SOURCE_DIR) + "/scenarios/small_basin.yaml";

std::string grid_sweep(const TempDir& tmp, const std::string& extra = "") {
  return write_text(tmp.file("grid.yaml"),
                    "scenario: " + kScenario +
                        "\n"
                        "runs: 2\n"
                        "methods: [deadreckoning, worldcentric]\n"
                        "grid:\n"
                        "  scenario.mru.heading_noise_deg: [0.5, 2]\n"
                        "  slam.trajectory_slam.max_matches_per_scan: [1, 3]\n" +
                        extra);
}

SweepOutcome run_sweep(const std::string& sweep_path, const fs::path& out,
                       const std::string& shard = "") {
  std::ostringstream log;
  return sweep({sweep_path, out.string(), 2, shard}, {log, false});
}

struct FullSweep {
  TempDir tmp;
  fs::path dir = tmp.path() / "sweep";
  SweepOutcome outcome = run_sweep(grid_sweep(tmp), dir);
};
const FullSweep& full_sweep() {
  static const FullSweep full;
  return full;
}

TEST(SweepCommand, GridCellsAndSweepCsv) {
  const FullSweep& full = full_sweep();
  EXPECT_EQ(full.outcome.cells, 4u);
  EXPECT_EQ(full.outcome.executed, 8u);
  EXPECT_EQ(full.outcome.failed, 0u);
  const results::SweepTable table = results::read_sweep_csv((full.dir / "sweep.csv").string());
  EXPECT_EQ(table.keys, (std::vector<std::string>{"scenario.mru.heading_noise_deg",
                                                  "slam.trajectory_slam.max_matches_per_scan"}));
  ASSERT_EQ(table.rows.size(), 8u);  // 4 cells x 2 methods, the last key fastest
  EXPECT_EQ(table.rows[2].cell, 1);
  EXPECT_EQ(table.rows[2].values, (std::vector<std::string>{"0.5", "3"}));
  EXPECT_EQ(table.rows[2].method, "deadreckoning");
  for (const results::SweepRow& r : table.rows) {
    EXPECT_EQ(r.runs, 2);
    EXPECT_EQ(r.failed, 0);
    ASSERT_TRUE(r.mean_error_m && r.p05_m && r.p95_m && r.anees);
    EXPECT_LE(*r.p05_m, *r.mean_error_m + 1e-12);
    EXPECT_GE(*r.p95_m, *r.mean_error_m - 1e-12);
    // Each cell's second method against its first, over the same runs.
    const bool first = r.method == table.rows[2 * r.cell].method;
    EXPECT_EQ(r.paired_reference, first ? "" : table.rows[2 * r.cell].method);
    EXPECT_EQ(r.paired_difference_m.has_value(), !first);
    if (!first) {
      EXPECT_LE(*r.paired_ci95_lower_m, *r.paired_difference_m);
      EXPECT_GE(*r.paired_ci95_upper_m, *r.paired_difference_m);
      EXPECT_LE(*r.paired_runs_lower, 2);
      // Every run finished: the mean difference is the difference of the means.
      EXPECT_NEAR(*r.paired_difference_m, *r.mean_error_m - *table.rows[2 * r.cell].mean_error_m,
                  1e-9);
    }
  }
  // The overrides took effect: each cell's inputs carry them, and the heading noise changes
  // dead reckoning (which no SLAM key touches) while the matches per scan do not.
  EXPECT_NE(
      read_text((full.dir / "inputs/cell_002/scenario.yaml").string()).find("heading_noise_deg: 2"),
      std::string::npos);
  EXPECT_NE(read_text((full.dir / "inputs/cell_002/config.yaml").string())
                .find("max_matches_per_scan: 1"),
            std::string::npos);
  EXPECT_EQ(table.rows[0].mean_error_m, table.rows[2].mean_error_m);  // DR, noise 0.5
  EXPECT_NE(table.rows[0].mean_error_m, table.rows[4].mean_error_m);  // DR, noise 0.5 vs 2
  EXPECT_TRUE(fs::exists(full.dir / "cells/cell_003/summary.json"));
  EXPECT_EQ(read_text((full.dir / "sweep.yaml").string()), read_text(full.tmp.file("grid.yaml")));
}

TEST(SweepCommand, ResumeRunsNothingNewAndShardsMergeToTheSameBytes) {
  const TempDir tmp;
  const fs::path dir = tmp.path() / "sweep";
  fs::copy(full_sweep().dir, dir, fs::copy_options::recursive);
  const std::string sweep_path = grid_sweep(tmp);
  // The copy's sweep.yaml must match the file given: the same text.
  const SweepOutcome again = run_sweep(sweep_path, dir);
  EXPECT_EQ(again.executed, 0u);
  const std::string full_csv = read_text((full_sweep().dir / "sweep.csv").string());
  EXPECT_EQ(read_text((dir / "sweep.csv").string()), full_csv);

  const fs::path s0 = tmp.path() / "s0", s1 = tmp.path() / "s1", merged = tmp.path() / "merged";
  EXPECT_EQ(run_sweep(sweep_path, s0, "0/2").executed, 4u);
  EXPECT_EQ(run_sweep(sweep_path, s1, "1/2").executed, 4u);
  const SweepOutcome m = merge_sweep(merged.string(), {s0.string(), s1.string()});
  EXPECT_EQ(m.cells, 4u);
  EXPECT_EQ(read_text((merged / "sweep.csv").string()), full_csv);
  EXPECT_EQ(read_text((merged / "cells/cell_001/nees.csv").string()),
            read_text((full_sweep().dir / "cells/cell_001/nees.csv").string()));
}

// Expects sweep() to throw InputError containing every word, without creating the directory.
void expect_rejected(const std::string& sweep_path, const fs::path& out,
                     const std::vector<std::string>& words) {
  try {
    run_sweep(sweep_path, out);
    ADD_FAILURE() << "no InputError for " << read_text(sweep_path);
  } catch (const io::InputError& e) {
    for (const std::string& w : words) {
      EXPECT_NE(std::string(e.what()).find(w), std::string::npos) << e.what();
    }
  }
  EXPECT_FALSE(fs::exists(out)) << read_text(sweep_path);
}

TEST(SweepCommand, BadInputIsRejectedBeforeAnythingRuns) {
  const TempDir tmp;
  const fs::path out = tmp.path() / "out";
  const std::string head = "scenario: " + kScenario + "\nruns: 2\n";
  const auto file = [&](const std::string& body) {
    return write_text(tmp.file("bad.yaml"), head + body);
  };
  expect_rejected(file("grid:\n  scenario.mru.heading_noise_deg: [1]\nrunz: 3\n"), out,
                  {"bad.yaml:", "runz"});
  expect_rejected(file("grid:\n  mru.heading_noise_deg: [1]\n"), out,
                  {"mru.heading_noise_deg", "scenario.<key path> or slam.<key path>"});
  expect_rejected(
      file("grid:\n  scenario.mru.heading_noise_degz: [1, 2]\n"), out,
      {"bad.yaml, cell 0 (scenario.mru.heading_noise_degz=1) scenario", "heading_noise_degz"});
  expect_rejected(file("grid:\n  slam.trajectory_slam.iekf_iterations: [0]\n"), out,
                  {"bad.yaml, cell 0", "iekf_iterations"});
  expect_rejected(file("grid:\n  scenario.mru.heading_noise_deg: []\n"), out, {"non-empty list"});
  expect_rejected(file("grid:\n  scenario.seed: [1]\ncells:\n  - {scenario.seed: 2}\n"), out,
                  {"exactly one of grid and cells"});
  expect_rejected(file("cells:\n  - {scenario.seed: 2}\n  - {scenario.seed: 2}\n"), out,
                  {"cells 0 and 1 are the same"});
  expect_rejected(file("methods: [bogus]\ncells:\n  - {scenario.seed: 2}\n"), out,
                  {"bogus", "not available"});
  expect_rejected(file("grid: {scenario.seed: [1]}\nscenario: [x]\n"), out, {"bad.yaml"});
  expect_rejected(write_text(tmp.file("bad.yaml"), "runs: 2\ngrid: {scenario.seed: [1]}\n"), out,
                  {"scenario", "is required"});

  // A directory of another sweep file is not resumed.
  const fs::path used = tmp.path() / "used";
  fs::copy(full_sweep().dir, used, fs::copy_options::recursive);
  try {
    run_sweep(file("cells:\n  - {scenario.seed: 5}\n"), used);
    ADD_FAILURE() << "resumed the cells of another sweep";
  } catch (const io::InputError& e) {
    EXPECT_NE(std::string(e.what()).find("another sweep"), std::string::npos) << e.what();
  }
}

// Through the executable: a sweep runs and says what it wrote; bad arguments exit 2 with one line.
TEST(SweepCli, RunsThroughTheExecutableAndRejectsBadArguments) {
  const TempDir tmp;
  const std::string sweep_path =
      write_text(tmp.file("one.yaml"),
                 "scenario: " + kScenario +
                     "\nruns: 1\nmethods: [deadreckoning]\ncells:\n  - {scenario.seed: 3}\n");
  const std::string out = tmp.file("out");
  const testing::CliResult ok = testing::run_msislab(
      "sweep " + testing::shell_quote(sweep_path) + " --no-plot --out " + testing::shell_quote(out),
      tmp);
  EXPECT_EQ(ok.exit_code, 0) << ok.err;
  EXPECT_NE(ok.out.find("sweep: " + out +
                        " holds 1 cells (1 runs done now, 0 with a failed "
                        "method); wrote sweep.csv"),
            std::string::npos)
      << ok.out;
  EXPECT_NE(ok.err.find("sweep: cell_000 (1/1): scenario.seed=3"), std::string::npos) << ok.err;
  for (const std::string& bad :
       {"sweep " + testing::shell_quote(sweep_path), std::string("sweep no_such.yaml --out o"),
        "sweep " + testing::shell_quote(sweep_path) + " --out o --shard 2/2",
        "sweep merge o " + testing::shell_quote(tmp.path().string())}) {
    const testing::CliResult result = testing::run_msislab(bad, tmp);
    EXPECT_EQ(result.exit_code, 2) << bad;
    EXPECT_EQ(std::count(result.err.begin(), result.err.end(), '\n'), 1) << bad << result.err;
    EXPECT_EQ(result.err.rfind("msislab: ", 0), 0u) << result.err;
  }
}

// A failed run in a cell (the workers' test hook, docs/cli.md): the sweep still writes sweep.csv
// with the failure counted, and exits 3 after one line naming the count and where the failed.json
// files are; a merge of it exits 3 too.
TEST(SweepCli, AFailedRunExits3WithSweepCsvWritten) {
  const TempDir tmp;
  const std::string sweep_path =
      write_text(tmp.file("two.yaml"),
                 "scenario: " + kScenario +
                     "\nruns: 2\nmethods: [deadreckoning]\ncells:\n  - {scenario.seed: 3}\n");
  const std::string out = tmp.file("out");
  const testing::CliResult failing = testing::run_msislab(
      "sweep " + testing::shell_quote(sweep_path) + " --no-plot --out " + testing::shell_quote(out),
      tmp, "env MSISLAB_MONTECARLO_FAULTS=1:deadreckoning:throw");
  EXPECT_EQ(failing.exit_code, 3) << failing.err;
  EXPECT_NE(failing.out.find("holds 1 cells (2 runs done now, 1 with a failed method); wrote "
                             "sweep.csv"),
            std::string::npos)
      << failing.out;
  const std::string last_line =
      "sweep: finished, but 1 of 2 runs have a failed method (exit status 3); see " + out +
      "/cells/*/runs/*/run_*/failed.json\n";
  ASSERT_GE(failing.err.size(), last_line.size());
  EXPECT_EQ(failing.err.substr(failing.err.size() - last_line.size()), last_line) << failing.err;
  EXPECT_TRUE(fs::exists(out + "/cells/cell_000/runs/deadreckoning/run_0001/failed.json"));
  const results::SweepTable table = results::read_sweep_csv(out + "/sweep.csv");
  ASSERT_EQ(table.rows.size(), 1u);
  EXPECT_EQ(table.rows[0].runs, 1);
  EXPECT_EQ(table.rows[0].failed, 1);
  EXPECT_TRUE(table.rows[0].mean_error_m.has_value());

  const std::string merged = tmp.file("merged");
  const testing::CliResult merge =
      testing::run_msislab("sweep merge " + testing::shell_quote(merged) + " " +
                               testing::shell_quote(out) + " --no-plot",
                           tmp);
  EXPECT_EQ(merge.exit_code, 3) << merge.err;
  EXPECT_NE(merge.err.find("sweep merge: finished, but 1 of 2 runs have a failed method"),
            std::string::npos)
      << merge.err;
  EXPECT_EQ(read_text(merged + "/sweep.csv"), read_text(out + "/sweep.csv"));
}

TEST(SweepYaml, CellsListAndGridOrder) {
  const TempDir tmp;
  const settings::Sweep grid = settings::read_sweep(
      write_text(tmp.file("g.yaml"),
                 "scenario: s.yaml\nruns: 1\ngrid:\n  slam.a: [1, 2]\n  scenario.b: "
                 "[x, [3, 4]]\n"));
  ASSERT_EQ(grid.cells.size(), 4u);
  EXPECT_EQ(settings::describe_cell(grid.cells[1]), "slam.a=1, scenario.b=[3, 4]");
  EXPECT_EQ(grid.cells[2].overrides[0].second.number, 2.0);
  EXPECT_FALSE(grid.cells[0].overrides[1].second.number);
  EXPECT_EQ(grid.scenario_path, (tmp.path() / "s.yaml").lexically_normal().string());
  EXPECT_EQ(grid.methods, (std::vector<std::string>{"robocentric", "worldcentric"}));
  const settings::Sweep list = settings::read_sweep(
      write_text(tmp.file("l.yaml"),
                 "scenario: s.yaml\nconfig: c.yaml\nruns: 3\nmethods: [deadreckoning]\n"
                 "cells:\n  - {slam.a: 1}\n  - {scenario.b: 2, slam.a: 5}\n"));
  EXPECT_EQ(list.keys, (std::vector<std::string>{"slam.a", "scenario.b"}));
  EXPECT_EQ(list.cells.size(), 2u);
  EXPECT_EQ(list.config_path, (tmp.path() / "c.yaml").lexically_normal().string());
}

// A cell's scenario is written into the sweep's own folder and read from there: every file the
// base scenario names (the replica's mesh and its heading history) must still be found.
TEST(SweepYaml, CellScenarioNamesItsFilesFromAnyFolder) {
  const TempDir tmp;
  const settings::Sweep sweep = settings::read_sweep(write_text(
      tmp.file("s.yaml"), "scenario: " + std::string(MSISLAB_SOURCE_DIR) +
                              "/scenarios/stpere_replica.yaml\nruns: 1\n"
                              "cells:\n  - {slam.trajectory_slam.iekf_iterations: 2}\n"));
  const settings::CellInputs inputs = settings::cell_inputs(sweep, 0);
  fs::create_directories(tmp.path() / "elsewhere");
  const sim::Scenario scenario = settings::read_scenario(
      write_text(tmp.file("elsewhere/scenario.yaml"), inputs.scenario_text));
  EXPECT_FALSE(scenario.vehicle.heading_deg.empty());
  EXPECT_TRUE(fs::path(scenario.scene.mesh_path).is_absolute());
}

}  // namespace
}  // namespace msislab::app
