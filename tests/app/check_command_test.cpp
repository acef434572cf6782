// `msislab check`: expectations met pass with exit 0 and JUnit XML without failures; a miss exits
// 1 with one stderr line per miss and a JUnit failure; run folders, folders of runs, Monte Carlo
// summaries and sweeps are read; a page that does not quote a claimed figure is a miss; malformed
// expectations, a figure that no result of any kind has and results not given exit 2 naming the
// file and line; a foreign JUnit file is refused.
#include <gtest/gtest.h>

#include <filesystem>
#include <string>

#include "cli_runner.hpp"
#include "results/montecarlo_files.hpp"
#include "results/results.hpp"
#include "results/sweep_files.hpp"
#include "test_support.hpp"

namespace msislab {
namespace {

namespace fs = std::filesystem;
using testing::CliResult;
using testing::read_text;
using testing::run_msislab;
using testing::shell_quote;
using testing::TempDir;
using testing::write_text;

/// A run folder of `method` with the given mean error, and 3 scans of NEES 1, 2, 3.
std::string make_run(const TempDir& tmp, const std::string& folder, const std::string& method,
                     double mean_error_m) {
  const fs::path dir = tmp.path() / folder;
  fs::create_directories(dir);
  RunMetrics m;
  m.method = method;
  m.truth = "simulation";
  m.errors = {10, mean_error_m, mean_error_m, mean_error_m, 2 * mean_error_m, mean_error_m};
  m.segments = {{"exit", 1.5 * mean_error_m}};
  m.scans = 3;
  m.anees = 2.0;
  results::write_metrics_json((dir / "metrics.json").string(), m, "/data/sim");
  results::write_nees_csv((dir / "nees.csv").string(), {{0.0, 1.0}, {1.0, 2.0}, {2.0, 3.0}});
  return dir.string();
}

/// A Monte Carlo summary of robocentric (first) and deadreckoning over 20 runs.
std::string make_montecarlo(const TempDir& tmp) {
  const fs::path dir = tmp.path() / "mc";
  fs::create_directories(dir);
  MethodSummary rc;
  rc.method = "robocentric";
  rc.runs = 20;
  rc.mean_error_m = 2.5;
  rc.anees = 3.1;
  rc.nees_in_bounds_fraction = 0.9;
  MethodSummary dr = rc;
  dr.method = "deadreckoning";
  dr.mean_error_m = 4.0;
  dr.anees = 9.0;
  dr.paired = PairedDifference{"robocentric", 20, 1.5, 0.5, 1.27, 1.73, 1};
  results::write_summary_json((dir / "summary.json").string(), {rc, dr});
  return dir.string();
}

CliResult check(const TempDir& tmp, const std::string& expectations, const std::string& results,
                const std::string& extra = "") {
  const std::string file = write_text(tmp.file("expect.yaml"), expectations);
  return run_msislab("check " + shell_quote(file) + " " + results + " " + extra, tmp);
}

TEST(CheckCommand, MetExpectationsPassAndWriteJunitWithoutFailures) {
  const TempDir tmp;
  const std::string run = make_run(tmp, "rc", "robocentric", 2.0);
  const CliResult r = check(tmp,
                            "expectations:\n"
                            "  - {metric: mean_error_m, at_most: 2.5}\n"
                            "  - {metric: segments.exit, equals: 3.0, tolerance: 0.001}\n"
                            "  - {anees_in_bounds: true}\n"
                            "  - {metric: nees_in_bounds_fraction, at_least: 0.66}\n",
                            shell_quote(run), "--junit " + shell_quote(tmp.file("j.xml")));
  EXPECT_EQ(r.exit_code, 0) << r.out << r.err;
  EXPECT_NE(r.out.find("4 of 4 expectations met, 0 missed"), std::string::npos) << r.out;
  const std::string xml = read_text(tmp.file("j.xml"));
  EXPECT_NE(xml.find("tests=\"4\" failures=\"0\""), std::string::npos) << xml;
  EXPECT_EQ(xml.find("<failure"), std::string::npos);
}

TEST(CheckCommand, AMissExitsOneWithALinePerMissAndAJunitFailure) {
  const TempDir tmp;
  const std::string run = make_run(tmp, "rc", "robocentric", 2.0);
  // The three scans' NEES (1, 2, 3) all lie inside one run's bounds [0.216, 9.35]: a fraction of
  // 1, so at_least 1.01 cannot hold.
  const CliResult r = check(tmp,
                            "expectations:\n"
                            "  - {name: small error, at_most: 1.5}\n"
                            "  - {name: fine, at_most: 2.5}\n"
                            "  - {name: too many, metric: nees_in_bounds_fraction, "
                            "at_least: 1.01}\n",
                            shell_quote(run), "--junit " + shell_quote(tmp.file("j.xml")));
  EXPECT_EQ(r.exit_code, 1) << r.out << r.err;
  EXPECT_NE(r.err.find("MISS small error: robocentric mean_error_m = 2, expected <= 1.5"),
            std::string::npos)
      << r.err;
  EXPECT_NE(r.err.find("MISS too many"), std::string::npos) << r.err;
  EXPECT_EQ(r.err.find("MISS fine"), std::string::npos) << r.err;
  const std::string xml = read_text(tmp.file("j.xml"));
  EXPECT_NE(xml.find("tests=\"3\" failures=\"2\""), std::string::npos) << xml;
  EXPECT_NE(xml.find("<failure message=\"robocentric mean_error_m = 2, expected &lt;= 1.5\""),
            std::string::npos)
      << xml;
}

TEST(CheckCommand, MonteCarloMethodsComparedAndPairedIntervalsRead) {
  const TempDir tmp;
  const std::string mc = make_montecarlo(tmp);
  const std::string expectations =
      "expectations:\n"
      "  - {method: robocentric, below: deadreckoning}\n"
      "  - {method: robocentric, anees_in_bounds: true}\n"
      "  - {method: deadreckoning, metric: paired_difference.ci95_lower_m, at_least: 0}\n"
      "  - {method: deadreckoning, anees_in_bounds: true}\n";
  const CliResult r = check(tmp, expectations, "sims=" + shell_quote(mc));
  EXPECT_EQ(r.exit_code, 1) << r.out << r.err;
  // 20 runs: the run-averaged NEES bounds are [2.14, 3.99] (average_chi2_bounds(20, 3)).
  EXPECT_NE(r.err.find("MISS deadreckoning anees: deadreckoning anees = 9, expected in "),
            std::string::npos)
      << r.err;
  EXPECT_NE(r.out.find("3 of 4 expectations met, 1 missed"), std::string::npos) << r.out;
}

TEST(CheckCommand, FolderOfRunsAndSweepCellsByName) {
  const TempDir tmp;
  make_run(tmp, "sim/rc", "robocentric", 2.0);
  make_run(tmp, "sim/dr", "deadreckoning", 3.0);
  const fs::path sweep = tmp.path() / "sweep";
  fs::create_directories(sweep);
  results::SweepTable table;
  table.keys = {"scenario.seed"};
  results::SweepRow row;
  row.values = {"1"};
  row.method = "robocentric";
  row.runs = 4;
  row.mean_error_m = 1.25;
  table.rows = {row};
  row.cell = 1;
  row.mean_error_m = 1.75;
  table.rows.push_back(row);
  results::write_sweep_csv((sweep / "sweep.csv").string(), table);
  const CliResult r = check(tmp,
                            "expectations:\n"
                            "  - {result: sim, method: robocentric, below: deadreckoning}\n"
                            "  - {result: sw, method: robocentric, cell: 1, equals: 1.75, "
                            "tolerance: 0}\n"
                            "  - {result: sw, method: robocentric, cell: 0, at_least: 1.5}\n",
                            shell_quote(tmp.file("sim")) + " sw=" + shell_quote(sweep.string()));
  EXPECT_EQ(r.exit_code, 1) << r.out << r.err;
  EXPECT_NE(r.err.find("MISS sw robocentric cell 0 mean_error_m"), std::string::npos) << r.err;
  EXPECT_NE(r.out.find("2 of 3 expectations met"), std::string::npos) << r.out;
}

TEST(CheckCommand, APageThatDoesNotQuoteTheFigureIsAMiss) {
  const TempDir tmp;
  const std::string run = make_run(tmp, "rc", "robocentric", 2.0);
  write_text(tmp.file("page.md"), "SLAM reaches\n2.00 m here.\n");
  const std::string quoted =
      "  - {name: q, equals: 2.00, tolerance: 0.005, quote: {file: page.md, text: "
      "'reaches {} m'}}\n";
  CliResult r = check(tmp, "expectations:\n" + quoted, shell_quote(run));
  EXPECT_EQ(r.exit_code, 0) << r.out << r.err;
  write_text(tmp.file("page.md"), "SLAM reaches 2.01 m here.\n");
  r = check(tmp, "expectations:\n" + quoted, "--partial");
  EXPECT_EQ(r.exit_code, 1) << r.out << r.err;
  EXPECT_NE(r.err.find("page.md does not quote \"reaches 2.00 m\""), std::string::npos) << r.err;
}

TEST(CheckCommand, BadExpectationsExitTwoNamingFileAndLine) {
  const TempDir tmp;
  const std::string run = make_run(tmp, "rc", "robocentric", 2.0);
  struct Case {
    std::string yaml, message;
  };
  const std::vector<Case> cases = {
      {"expectations:\n  - metric: mean_error_m\n    at_mots: 3\n",
       "expect.yaml:3: key 'expectations[0].at_mots': unknown key (did you mean 'at_most'?)"},
      {"expectations:\n  - {at_most: .nan}\n", "expect.yaml:2: key 'expectations[0].at_most'"},
      {"expectations:\n  - metric: mean_error_m\n",
       "expect.yaml:2: an expectation states "
       "nothing to check"},
      {"expectations:\n  - {equals: 2}\n", "key 'expectations[0].tolerance'"},
      {"expectations: [\n", "expect.yaml:"},
      {"expectation:\n  - {at_most: 2}\n", "expect.yaml"},
      {"expectations:\n  - {result: mc, at_most: 2}\n",
       "expect.yaml:2: result 'mc' was not given (given: rc"},
      // A figure no result of any kind has is a misspelling, not a regression of the SLAM.
      {"expectations:\n  - {metric: mean_eror_m, at_most: 3}\n",
       "expect.yaml:2: key 'expectations[0].metric': no result of any kind has a figure "
       "'mean_eror_m' (did you mean 'mean_error_m'?)"},
      {"expectations:\n  - {metric: wobble, at_most: 3}\n",
       "no result of any kind has a figure 'wobble' (see docs/cli.md"},
  };
  for (const Case& c : cases) {
    const CliResult r = check(tmp, c.yaml, shell_quote(run));
    EXPECT_EQ(r.exit_code, 2) << c.yaml << r.err;
    EXPECT_NE(r.err.find(c.message), std::string::npos) << c.yaml << r.err;
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
  }
}

TEST(CheckCommand, AForeignJunitFileIsRefusedAndKept) {
  const TempDir tmp;
  const std::string run = make_run(tmp, "rc", "robocentric", 2.0);
  write_text(tmp.file("mine.xml"), "<results>mine</results>\n");
  const CliResult r = check(tmp, "expectations:\n  - {at_most: 1}\n", shell_quote(run),
                            "--junit " + shell_quote(tmp.file("mine.xml")));
  EXPECT_EQ(r.exit_code, 2) << r.err;
  EXPECT_NE(r.err.find("mine.xml"), std::string::npos) << r.err;
  EXPECT_EQ(read_text(tmp.file("mine.xml")), "<results>mine</results>\n");
}

}  // namespace
}  // namespace msislab
