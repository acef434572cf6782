// `msislab report`: the results page from result folders and a Monte Carlo directory written by
// the io writers. The tables list the methods in a fixed order with the segment columns the results
// name, ANEES only where there is pose truth, the Monte Carlo bounds for its number of runs and the
// robocentric/world-centric verdict; the figures are copied beside the page under their labels and
// replace the earlier ones whole; bad input names the folder and leaves the page as it was.
#include "app/report_command.hpp"

#include <gtest/gtest.h>

#include <chrono>
#include <filesystem>
#include <string>

#include "cli_runner.hpp"
#include "io/input_error.hpp"
#include "io/output_guard.hpp"
#include "io/sensitivity_csv.hpp"
#include "results/montecarlo_files.hpp"
#include "results/results.hpp"
#include "results/sweep_files.hpp"
#include "test_support.hpp"

namespace msislab::app {
namespace {

namespace fs = std::filesystem;
using testing::read_text;
using testing::TempDir;
using testing::write_text;

RunMetrics metrics(const std::string& method, double mean_m, std::optional<double> anees,
                   std::optional<double> canal_m) {
  RunMetrics m;
  m.method = method;
  m.truth = anees ? "simulation" : "gps";
  m.errors.mean_m = mean_m;
  m.errors.final_m = 2.0 * mean_m;
  m.errors.max_m = 3.0 * mean_m;
  m.segments = {{"loop", 0.5 * mean_m}, {"canal", canal_m}};
  m.anees = anees;
  m.runtime_s = 1.25;
  if (method != "deadreckoning") {
    m.scans = 236;
    m.matches_accepted = 697;
  }
  return m;
}

/// A folder of results: one subdirectory per method with trajectory.tum and metrics.json, and
/// figures/.
fs::path result_folder(const fs::path& dir, const std::vector<RunMetrics>& results,
                       const std::vector<std::string>& figures,
                       const std::string& dataset = "/data/stpere_replica") {
  for (const RunMetrics& m : results) {
    fs::create_directories(dir / m.method);
    write_text((dir / m.method / "trajectory.tum").string(), "0 0 0 0 0 0 0 1\n1 1 0 0 0 0 0 1\n");
    results::write_metrics_json((dir / m.method / "metrics.json").string(), m, dataset);
  }
  fs::create_directories(dir / "figures");
  for (const std::string& f : figures) write_text((dir / "figures" / f).string(), "png " + f);
  return dir;
}

fs::path montecarlo_folder(const fs::path& dir, double rc_anees, double wc_anees,
                           double rc_fraction = 0.5,
                           const std::string& scenario = "stpere_replica.yaml") {
  fs::create_directories(dir / "figures");
  results::MonteCarloManifest manifest;
  manifest.scenario_source = "/src/scenarios/" + scenario;
  manifest.first_seed = 42;
  manifest.runs = 50;
  manifest.methods = {"robocentric", "worldcentric"};
  results::write_manifest_json((dir / "montecarlo.json").string(), manifest);
  std::vector<MethodSummary> methods(2);
  for (int i = 0; i < 2; ++i) {
    MethodSummary& s = methods[i];
    s.method = i == 0 ? "robocentric" : "worldcentric";
    s.runs = 50;
    s.mean_error_m = 2.574;
    s.anees = i == 0 ? rc_anees : wc_anees;
    s.nees_in_bounds_fraction = i == 0 ? rc_fraction : 0.072;
    s.nees.resize(236);
    s.segments = {{"loop", 1.2}, {"canal", 4.47}};
    s.runtime_s = 250.0;
  }
  results::write_summary_json((dir / "summary.json").string(), methods);
  write_text((dir / "figures" / "nees.png").string(), "png nees");
  return dir;
}

struct Inputs {
  TempDir tmp;
  fs::path sim, real, mc;
  Inputs() {
    sim = result_folder(
        tmp.path() / "sim",
        {metrics("deadreckoning", 6.28, 2.9, 9.22), metrics("worldcentric", 2.163, 13.98, 3.844),
         metrics("robocentric", 2.163, 13.98, 3.844)},
        {"robocentric.png", "errors.png", "deadreckoning.png", "extra.png"});
    real = result_folder(tmp.path() / "real",
                         {metrics("robocentric", 3.99, std::nullopt, std::nullopt),
                          metrics("deadreckoning", 3.56, std::nullopt, 4.13)},
                         {"errors.png"});
    mc = montecarlo_folder(tmp.path() / "mc", 5.0, 18.68);
  }
  ReportOptions options() const {
    return {tmp.file("docs/results.md"), sim.string(), real.string(), {mc.string()}, {}, ""};
  }
};

std::size_t position(const std::string& text, const std::string& part) {
  const std::size_t at = text.find(part);
  EXPECT_NE(at, std::string::npos) << "no '" << part << "' in\n" << text;
  return at;
}

/// write_report(options) throws an InputError whose message holds `part`.
void expect_error(const ReportOptions& options, const std::string& part) {
  try {
    write_report(options);
    ADD_FAILURE() << "no InputError, expected " << part;
  } catch (const io::InputError& e) {
    EXPECT_NE(std::string(e.what()).find(part), std::string::npos) << e.what();
  }
}

TEST(ReportCommand, TablesFiguresAndVerdict) {
  const Inputs in;
  fs::create_directories(in.tmp.path() / "docs");
  // A result without truth has no metrics.json and no row.
  fs::create_directories(in.sim / "no_truth");
  write_text((in.sim / "no_truth" / "trajectory.tum").string(), "0 0 0 0 0 0 0 1\n");
  const ReportOutcome outcome = write_report(in.options());
  const std::string page = read_text(in.tmp.file("docs/results.md"));
  // Table I on simulated data: robocentric, world-centric, dead reckoning; the segments as
  // columns, with ANEES.
  EXPECT_NE(page.find("| method | mean error [m] | loop [m] | canal [m] | final [m] | max [m] | "
                      "scans | matches accepted | ANEES | run time [s] |"),
            std::string::npos)
      << page;
  const std::size_t rc = position(page,
                                  "| Robocentric SLAM | **2.16** | 1.08 | 3.84 | 4.33 | 6.49 | "
                                  "236 | 697 | 13.98 | 1.25 |");
  const std::size_t wc = position(page, "| World-centric SLAM | **2.16** |");
  const std::size_t dr = position(page,
                                  "| Dead reckoning | **6.28** | 3.14 | 9.22 | 12.56 | "
                                  "18.84 |  |  | 2.90 | 1.25 |");
  EXPECT_LT(rc, wc);
  EXPECT_LT(wc, dr);
  EXPECT_EQ(page.find("no_truth"), std::string::npos);
  position(page, "2.16 against 2.16 m mean error (the same within 1 cm)");
  position(page, "2.16 against 6.28 m mean error (-66 %); loop 1.08 against 3.14 m");
  // Real data: no ANEES column, a null segment shown as n/a, the paper's figures.
  position(page, "scans | matches accepted | run time [s] |\n");
  position(page, "| Robocentric SLAM | **3.99** | 2.00 | n/a |");
  position(page, "robocentric 1.15 m, world-centric 2.05 m");
  // Monte Carlo: 50 runs, seeds, bounds for 50 runs of 3 DOF, run time per run, the verdict.
  position(page, "50 seeded runs of the scenario `stpere_replica.yaml` (seeds 42 to 91)");
  position(page,
           "| Robocentric SLAM | 50 | 0 | 2.57 | 1.20 | 4.47 | 5.00 | 50.0 % of 236 | "
           "[2.36, 3.72] | 5.00 |");
  position(page, "the robocentric filter is the more consistent one here");
  // Figures: the known ones in the (a)-(d) order, then the others; copied under their labels.
  const std::size_t a = position(page, "(a) Dead reckoning against the simulation truth");
  const std::size_t c = position(page, "(c) Robocentric SLAM");
  const std::size_t d = position(page, "(d) Position error");
  const std::size_t extra = position(page, "](results/sim_extra.png)");
  EXPECT_TRUE(a < c && c < d && d < extra);
  position(page, "](results/real_errors.png)");
  position(page, "](results/montecarlo_nees.png)");
  EXPECT_EQ(outcome.figures.size(), 6u);
  EXPECT_EQ(read_text(in.tmp.file("docs/results/sim_robocentric.png")), "png robocentric.png");
  EXPECT_EQ(read_text(in.tmp.file("docs/results/montecarlo_nees.png")), "png nees");
}

TEST(ReportCommand, VerdictFollowsTheFigures) {
  const Inputs in;
  montecarlo_folder(in.mc, 18.68, 18.68, 0.072);
  write_report(in.options());
  EXPECT_NE(read_text(in.tmp.file("docs/results.md")).find("is equally consistent here"),
            std::string::npos);
  montecarlo_folder(in.mc, 40.0, 18.68);
  write_report(in.options());
  EXPECT_NE(read_text(in.tmp.file("docs/results.md")).find("is neither clearly more nor less"),
            std::string::npos);
}

TEST(ReportCommand, FurtherMonteCarloFoldersGetSectionsOfTheirOwn) {
  const Inputs in;
  const fs::path channel =
      montecarlo_folder(in.tmp.path() / "channel", 2.86, 2.86, 0.906, "straight_channel.yaml");
  ReportOptions options = in.options();
  options.montecarlo_dirs.push_back(channel.string());
  const ReportOutcome outcome = write_report(options);
  const std::string page = read_text(in.tmp.file("docs/results.md"));
  const std::size_t first = position(page,
                                     "## Monte Carlo consistency\n\n50 seeded runs of the "
                                     "scenario `stpere_replica.yaml`");
  const std::size_t second =
      position(page,
               "## Monte Carlo consistency: `straight_channel.yaml`\n\n50 seeded runs of "
               "the scenario `straight_channel.yaml`");
  EXPECT_LT(first, second);
  EXPECT_LT(position(page, "](results/montecarlo_nees.png)"), second);
  EXPECT_GT(position(page, "](results/montecarlo_straight_channel_nees.png)"), second);
  EXPECT_EQ(outcome.figures.size(), 7u);
  EXPECT_TRUE(fs::exists(in.tmp.path() / "docs/results/montecarlo_straight_channel_nees.png"));

  options.montecarlo_dirs.push_back(channel.string());  // the same scenario twice
  fs::remove_all(in.tmp.path() / "docs");
  try {
    write_report(options);
    ADD_FAILURE() << "no InputError for a scenario given twice";
  } catch (const io::InputError& e) {
    EXPECT_NE(std::string(e.what()).find("a second Monte Carlo of"), std::string::npos) << e.what();
  }
  EXPECT_FALSE(fs::exists(in.tmp.path() / "docs" / "results.md"));
}

TEST(ReportCommand, FiguresReplaceTheEarlierOnesWhole) {
  const Inputs in;
  write_report(in.options());  // the earlier page and its figures
  ASSERT_TRUE(fs::exists(in.tmp.path() / "docs" / "results" / "sim_robocentric.png"));
  ReportOptions only_real = in.options();
  only_real.sim_dir.clear();
  only_real.montecarlo_dirs.clear();
  write_report(only_real);
  EXPECT_FALSE(fs::exists(in.tmp.path() / "docs" / "results" / "sim_robocentric.png"));
  EXPECT_TRUE(fs::exists(in.tmp.path() / "docs" / "results" / "real_errors.png"));
  // Sections appear for what was asked, and nothing else.
  const std::string page = read_text(in.tmp.file("docs/results.md"));
  EXPECT_EQ(page.find("## Table I on the simulated"), std::string::npos) << page;
  EXPECT_EQ(page.find("## Monte Carlo consistency"), std::string::npos) << page;
  EXPECT_EQ(page.find("Not run"), std::string::npos) << page;
}

TEST(ReportCommand, AForeignFiguresFolderOrPageIsRefusedAndKept) {
  const Inputs in;
  fs::create_directories(in.tmp.path() / "docs" / "results");
  write_text(in.tmp.file("docs/results/figure.png"), "the user's");
  expect_error(in.options(), "docs/results: is a folder that msislab did not write");
  EXPECT_EQ(read_text(in.tmp.file("docs/results/figure.png")), "the user's");
  EXPECT_FALSE(fs::exists(in.tmp.path() / "docs" / "results.md"));
  fs::remove_all(in.tmp.path() / "docs" / "results");
  write_text(in.tmp.file("docs/results.md"), "# the user's page\n");
  expect_error(in.options(), "docs/results.md: is a file that msislab did not write");
  EXPECT_EQ(read_text(in.tmp.file("docs/results.md")), "# the user's page\n");
  EXPECT_FALSE(fs::exists(in.tmp.path() / "docs" / "results"));
}

TEST(ReportCommand, AUsersOwnScenarioIsTitledByItsName) {
  const TempDir tmp;
  const fs::path dataset = tmp.path() / "basin_sim";
  fs::create_directories(dataset);
  write_text((dataset / "basin_pier_DVL.log").string(), "");
  const RunMetrics m = metrics("robocentric", 0.76, 3.1, std::nullopt);
  const fs::path sim =
      result_folder(tmp.path() / "sim", {m}, {"robocentric.png"}, dataset.string());
  ReportOptions options;
  options.out_path = tmp.file("page.md");
  options.sim_dir = sim.string();
  write_report(options);
  const std::string page = read_text(options.out_path);
  position(page, "## Table I on the simulated dataset `basin_pier`");
  EXPECT_EQ(page.find("St. Pere"), std::string::npos) << page;
  EXPECT_EQ(page.find("1.15 m"), std::string::npos) << page;
  EXPECT_EQ(page.find("Not run"), std::string::npos) << page;
}

TEST(ReportCommand, ThePoseGraphsSmoothedErrorBesideItsOnlineOne) {
  const TempDir tmp;
  RunMetrics graph = metrics("posegraph", 2.63, std::nullopt, 4.47);
  graph.diagnostics = {{"matches_downweighted", 0}, {"smoothed_mean_error_m", 2.716}};
  const fs::path real =
      result_folder(tmp.path() / "real", {metrics("robocentric", 2.84, std::nullopt, 4.47), graph},
                    {"posegraph.png"});
  ReportOptions options;
  options.out_path = tmp.file("page.md");
  options.real_dir = real.string();
  write_report(options);
  const std::string page = read_text(options.out_path);
  position(page, "| Robocentric SLAM | **2.84** |");
  position(page, "| Pose graph (Ceres) | **2.63** |");  // the registry's order
  position(page,
           "- Pose graph (Ceres): 2.72 m mean error smoothed (trajectory_smoothed.tum), "
           "2.63 m online");
  position(page, "**The pose graph (online) against the GPS track, 2-sigma ellipses");
}

TEST(ReportCommand, SweepTablesMarkTheDifferencesBeyondTheNoise) {
  const TempDir tmp;
  const fs::path dir = tmp.path() / "heading_noise";
  fs::create_directories(dir);
  results::SweepTable table;
  table.keys = {"scenario.mru.heading_noise_deg"};
  for (int cell = 0; cell < 2; ++cell) {
    results::SweepRow rc;
    rc.cell = cell;
    rc.values = {cell == 0 ? "1" : "30"};
    rc.method = "robocentric";
    rc.runs = 20;
    rc.mean_error_m = 0.7 + cell;
    rc.anees = 3.4;
    rc.linearisation_observation = 1e-4;
    rc.linearisation_inversion = 2e-4;
    rc.linearisation_pose = 3e-4;
    results::SweepRow wc = rc;
    wc.method = "worldcentric";
    wc.linearisation_inversion.reset();
    wc.paired_reference = "robocentric";
    wc.paired_difference_m = cell == 0 ? 0.0001 : 0.05;
    wc.paired_ci95_lower_m = cell == 0 ? -0.001 : 0.01;
    wc.paired_ci95_upper_m = cell == 0 ? 0.001 : 0.09;
    wc.paired_runs_lower = 3;
    table.rows.push_back(rc);
    table.rows.push_back(wc);
  }
  results::write_sweep_csv((dir / "sweep.csv").string(), table);
  ReportOptions options;
  options.out_path = tmp.file("page.md");
  options.sweep_dirs = {dir.string()};
  write_report(options);
  const std::string page = read_text(options.out_path);
  EXPECT_NE(page.find("## Sweep: `heading_noise`"), std::string::npos) << page;
  EXPECT_NE(page.find("| heading_noise_deg | Robocentric SLAM [m] | World-centric SLAM [m] | "
                      "World-centric SLAM minus Robocentric SLAM [mm] | ANEES | epsilon: match "
                      "update | inversion | pose read-out |"),
            std::string::npos)
      << page;
  EXPECT_NE(page.find("| 1 | 0.700 | 0.700 | 0.1 [-1.0, 1.0] | 3.40 / 3.40 | 1.0e-04 / "
                      "1.0e-04 | 2.0e-04 | 3.0e-04 / 3.0e-04 |"),
            std::string::npos)
      << page;
  EXPECT_NE(page.find("| 30 | 1.700 | 1.700 | **50.0 [10.0, 90.0]** |"), std::string::npos) << page;
  EXPECT_NE(page.find("beyond the Monte Carlo noise (95 % interval without 0, in bold): cell 1 "
                      "(worldcentric)."),
            std::string::npos)
      << page;
  options.sweep_dirs = {tmp.file("nowhere")};
  EXPECT_THROW(write_report(options), io::InputError);
}

TEST(ReportCommand, SensitivityTableMarksTheCliffs) {
  // tools/real_sensitivity.sh --csv: a parameter whose 10 % change moves the error by more than a
  // quarter is in bold and counted; a bad table names its file and line.
  const Inputs in;
  ReportOptions options = in.options();
  options.sensitivity_csv = write_text(
      in.tmp.file("sensitivity.csv"),
      std::string(io::kSensitivityHeader) +
          "\ntrajectory_slam.innovation_gate_chi2,11.34,robocentric,2.84,10.206,4.65,12.474,2.82\n"
          "segmentation.sigma_range_m,0.1,robocentric,2.84,0.09,2.83,0.11,2.88\n");
  write_report(options);
  const std::string page = read_text(options.out_path);
  EXPECT_NE(page.find("## How far the real result can be trusted"), std::string::npos);
  EXPECT_NE(
      page.find("| `trajectory_slam.innovation_gate_chi2` | 11.34 | Robocentric SLAM | 2.84 | "
                "10.206 | **4.65 (+64 %)** | 12.474 | 2.82 (-1 %) |"),
      std::string::npos)
      << page;
  EXPECT_NE(page.find("| 0.09 | 2.83 (0 %) | 0.11 | 2.88 (+1 %) |"), std::string::npos) << page;
  EXPECT_NE(page.find("more than 25 %: 1 of 2."), std::string::npos) << page;

  write_text(options.sensitivity_csv, std::string(io::kSensitivityHeader) +
                                          "\ngate,11.34,robocentric,2.84,10.2,nan,12.5,2.8\n");
  expect_error(options, "sensitivity.csv:2: field 6 (low_mean_error_m) 'nan'");
  write_text(options.sensitivity_csv, "parameter,value\n");
  expect_error(options, "sensitivity.csv:1: wrong header");
  write_text(options.sensitivity_csv, std::string(io::kSensitivityHeader) + "\ngate,11.34\n");
  expect_error(options, "sensitivity.csv:2: truncated line");
}

TEST(ReportCommand, BadInputNamesTheFolderAndWritesNothing) {
  const Inputs in;
  fs::create_directories(in.tmp.path() / "docs");
  const std::string earlier = io::page_signature("report") + "the earlier page\n";
  const std::string page = write_text(in.tmp.file("docs/results.md"), earlier);
  // Each bad input is an error, and the earlier page and no figures folder are left.
  const auto expect_error_and_nothing_written = [&](const ReportOptions& options,
                                                    const std::string& part) {
    expect_error(options, part);
    EXPECT_EQ(read_text(page), earlier);
    EXPECT_FALSE(fs::exists(in.tmp.path() / "docs" / "results"));
  };
  ReportOptions options = in.options();
  fs::remove_all(in.real / "figures");
  expect_error_and_nothing_written(
      options, (in.real / "figures").string() + ": no figures (draw them first");
  options.real_dir = in.tmp.file("nowhere");
  expect_error_and_nothing_written(options, in.tmp.file("nowhere") + ": not a directory");
  options = in.options();
  options.real_dir.clear();
  fs::remove(in.mc / "summary.json");
  expect_error_and_nothing_written(options, "summary.json: missing");
  write_text((in.sim / "robocentric" / "metrics.json").string(), "{\"method\": 3}\n");
  options.montecarlo_dirs.clear();
  expect_error_and_nothing_written(options, "metrics.json");
  expect_error_and_nothing_written(ReportOptions{page, "", "", {}, {}, ""}, "nothing to report");
}

TEST(ReportCommand, FiguresDrawnBeforeTheirDataAreRefused) {
  // A Monte Carlo resumed with another method after its figures were drawn, a result scored again:
  // the page would show figures without it. Named, with how to draw them again.
  const Inputs in;
  const fs::path nees = in.mc / "figures" / "nees.png";
  fs::last_write_time(nees, fs::last_write_time(in.mc / "summary.json") - std::chrono::seconds(5));
  expect_error(in.options(),
               nees.string() + ": was drawn before " + (in.mc / "summary.json").string() +
                   " was written (draw the figures again: msislab plot " + in.mc.string() + ")");
  EXPECT_FALSE(fs::exists(in.tmp.path() / "docs" / "results.md"));
  fs::last_write_time(nees, fs::last_write_time(in.mc / "summary.json"));
  const fs::path errors = in.real / "figures" / "errors.png";
  fs::last_write_time(errors, fs::last_write_time(in.real / "robocentric" / "metrics.json") -
                                  std::chrono::seconds(5));
  expect_error(in.options(), errors.string() + ": was drawn before");
}

TEST(ReportCli, ExitsTwoWithOneLineOnBadInput) {
  const TempDir tmp;
  const testing::CliResult result =
      testing::run_msislab("report " + testing::shell_quote(tmp.file("r.md")) + " --sim " +
                               testing::shell_quote(tmp.file("missing")),
                           tmp);
  EXPECT_EQ(result.exit_code, 2);
  EXPECT_EQ(result.err, "msislab: " + tmp.file("missing") + ": not a directory\n");
  EXPECT_FALSE(fs::exists(tmp.file("r.md")));
}

}  // namespace
}  // namespace msislab::app
