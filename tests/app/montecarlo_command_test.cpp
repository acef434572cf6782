// `msislab montecarlo` end to end on small_basin (3 runs of deadreckoning and worldcentric, about
// 2 s each): the summary and run directories, seeds, resuming, shards merged into the same bytes,
// failed runs recorded while the others finish, and bad input rejected before anything runs.
#include "app/montecarlo.hpp"

#include <fcntl.h>
#include <gtest/gtest.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <csignal>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <map>
#include <regex>
#include <sstream>
#include <string>
#include <thread>

#include "app/montecarlo_directory.hpp"
#include "app/process.hpp"
#include "app/run_command.hpp"
#include "app/simulate_command.hpp"
#include "cli_runner.hpp"
#include "io/input_error.hpp"
#include "io/json.hpp"
#include "io/text_lines.hpp"
#include "results/results.hpp"
#include "slam/scan_matching.hpp"
#include "stats/chi_square.hpp"
#include "test_support.hpp"

namespace msislab::app {
namespace {

namespace fs = std::filesystem;
using testing::read_text;
using testing::TempDir;
using testing::write_text;

const std::string kScenario = std::string(MSISLAB_SOURCE_DIR) + "/scenarios/small_basin.yaml";
const std::vector<std::string> kMethods = {"deadreckoning", "worldcentric"};

MonteCarloOptions options_for(const fs::path& out, const std::string& shard = "") {
  MonteCarloOptions options;
  options.scenario_path = kScenario;
  options.runs = 3;
  options.out_dir = out.string();
  options.methods = kMethods;
  options.jobs = 2;
  options.shard = shard;
  return options;
}

struct Logged {
  std::ostringstream log;
  MonteCarloOutcome outcome;
};

std::unique_ptr<Logged> run_montecarlo(const MonteCarloOptions& options) {
  auto logged = std::make_unique<Logged>();
  logged->outcome = montecarlo(options, {logged->log, false});
  return logged;
}

// One full 3-run directory, shared by the tests that only read it or copy it.
struct FullRun {
  TempDir tmp;
  fs::path dir = tmp.path() / "mc";
  std::unique_ptr<Logged> logged = run_montecarlo(options_for(dir));
};
const FullRun& full_run() {
  static const FullRun full;
  return full;
}

// The text without the lines that hold a run time.
std::string without_runtimes(const std::string& text) {
  std::istringstream in(text);
  std::string line, out;
  while (std::getline(in, line)) {
    if (line.find("runtime_s") == std::string::npos) out += line + "\n";
  }
  return out;
}

std::map<std::string, fs::file_time_type> metrics_mtimes(const fs::path& dir) {
  std::map<std::string, fs::file_time_type> times;
  for (const auto& entry : fs::recursive_directory_iterator(dir / "runs")) {
    if (entry.path().filename() == "metrics.json") {
      times[entry.path().string()] = fs::last_write_time(entry.path());
    }
  }
  return times;
}

TEST(MonteCarloCommand, SummaryAndRunDirectories) {
  const FullRun& full = full_run();
  const MonteCarloOutcome& outcome = full.logged->outcome;
  EXPECT_EQ(outcome.runs, 3u);
  EXPECT_EQ(outcome.executed, 3u);
  EXPECT_EQ(outcome.failed, 0u);
  EXPECT_NE(full.logged->log.str().find("montecarlo: 3/3 runs done, 0 failed, elapsed "),
            std::string::npos)
      << full.logged->log.str();

  const std::string summary_path = (full.dir / "summary.json").string();
  const io::Json root = io::read_json_file(summary_path);
  const io::JsonObject summary(root, summary_path);
  ASSERT_EQ(root.size(), 2u);
  EXPECT_EQ(root.begin().key(), "deadreckoning");
  EXPECT_EQ(std::next(root.begin()).key(), "worldcentric");
  for (const std::string& method : kMethods) {
    const io::JsonObject m = summary.object(method);
    EXPECT_EQ(m.number("runs"), 3);
    EXPECT_EQ(m.number("failed"), 0);
    EXPECT_GT(m.number("mean_error_m"), 0.1);
    EXPECT_LT(m.number("mean_error_m"), 5.0);
    EXPECT_GT(m.number("runtime_s"), 0.0);
    EXPECT_TRUE(m.has("segments"));
  }
  const io::JsonObject dr = summary.object("deadreckoning");
  // Dead reckoning's scan poses are scored too (the scans it places from the sonar data). Its
  // noise model is not the simulator's (white heading noise of 1 deg against 0.04 deg and a bias
  // random walk, a Gaussian DVL against a heavy-tailed one: docs/dead_reckoning.md), so no
  // consistency is claimed: a regression guard of a deterministic figure, golden for one build
  // (tests/golden/montecarlo_small_basin.yaml says which, and how to regenerate it).
  const std::string golden =
      read_text(std::string(MSISLAB_SOURCE_DIR) + "/tests/golden/montecarlo_small_basin.yaml");
  std::smatch build, anees;
  ASSERT_TRUE(std::regex_search(golden, build, std::regex(R"(\nbuild: ([^#\n]*[^#\n ]))")));
  ASSERT_TRUE(std::regex_search(golden, anees, std::regex(R"(\ndeadreckoning_anees: ([0-9.]+))")));
  if (build[1].str() == MSISLAB_BUILD) {
    const double golden_anees = std::stod(anees[1].str());
    EXPECT_NEAR(dr.number("anees"), golden_anees, 1e-9 * golden_anees);
  } else {
    std::cout << "golden figures are of " << build[1].str() << ", this build is " << MSISLAB_BUILD
              << ": dead reckoning's ANEES " << dr.number("anees") << " not compared\n";
  }
  // The SLAM filter is expected consistent: 3 runs times the ANEES is chi-square with 3 x 3 DOF
  // at every scan, and the 6 scans of a run are correlated (their errors accumulate), so the
  // widest case, all 6 one variable, bounds the ANEES: average_chi2_bounds(3, 3) = [0.90, 6.34]
  // (measured 1.58).
  const io::JsonObject wc = summary.object("worldcentric");
  const auto [lower_3_runs, upper_3_runs] = average_chi2_bounds(3, 3, 0.05);
  EXPECT_GT(wc.number("anees"), lower_3_runs);
  EXPECT_LT(wc.number("anees"), upper_3_runs);
  EXPECT_LT(wc.number("mean_error_m"), dr.number("mean_error_m"));

  // nees.csv: one row per scan index and method, averaged over the 3 runs (dead reckoning's
  // scans are the ones it places from the sonar data).
  const std::string nees = read_text((full.dir / "nees.csv").string());
  EXPECT_EQ(nees.rfind("method,scan,runs,mean_nees,lower,upper\ndeadreckoning,0,3,", 0), 0u)
      << nees;
  EXPECT_NE(nees.find("\nworldcentric,0,3,"), std::string::npos);
  EXPECT_EQ(static_cast<double>(std::count(nees.begin(), nees.end(), '\n') - 1),
            dr.number("nees_scans") + wc.number("nees_scans"));
  EXPECT_NE(
      nees.find(io::format_number(lower_3_runs) + "," + io::format_number(upper_3_runs) + "\n"),
      std::string::npos);
  // The summary's in-bounds fraction is nees.csv's share of worldcentric rows inside their bounds.
  int wc_rows = 0, wc_inside = 0;
  std::istringstream rows(nees);
  for (std::string line; std::getline(rows, line);) {
    if (line.rfind("worldcentric,", 0) != 0) continue;
    const auto f = io::split_csv<6>(line, "nees.csv", 0);
    const double mean = std::stod(std::string(f[3]));
    ++wc_rows;
    wc_inside += mean >= std::stod(std::string(f[4])) && mean <= std::stod(std::string(f[5]));
  }
  ASSERT_GT(wc_rows, 0);
  EXPECT_DOUBLE_EQ(wc.number("nees_in_bounds_fraction"), static_cast<double>(wc_inside) / wc_rows);

  // Run directories, the scenario copy and the seeds; no scratch datasets or maps left.
  for (const std::string& method : kMethods) {
    for (int r = 0; r < 3; ++r) {
      const fs::path rd(run_dir(full.dir.string(), method, r));
      EXPECT_TRUE(fs::is_regular_file(rd / "metrics.json")) << rd;
      EXPECT_TRUE(fs::is_regular_file(rd / "trajectory.tum")) << rd;
      EXPECT_TRUE(fs::exists(rd / "nees.csv")) << rd;
      EXPECT_FALSE(fs::exists(rd / "map.ply")) << rd;
      EXPECT_FALSE(fs::exists(rd / "failed.json")) << rd;
    }
  }
  EXPECT_FALSE(fs::exists(full.dir / "scratch"));
  EXPECT_EQ(read_text((full.dir / "scenario.yaml").string()), read_text(kScenario));
  EXPECT_EQ(read_text((full.dir / "seeds.csv").string()), "run,seed\n0,1\n1,2\n2,3\n");
}

TEST(MonteCarloCommand, RunRIsTheScenarioSimulatedWithSeedPlusR) {
  const FullRun& full = full_run();
  const TempDir tmp;
  simulate({kScenario, tmp.file("dataset"), 3, 2});  // small_basin's seed is 1: run 2
  run({tmp.file("dataset"), "worldcentric", tmp.file("wc"), ""});
  const results::StoredMetrics direct = results::read_metrics_json(tmp.file("wc/metrics.json"));
  const results::StoredMetrics in_mc = results::read_metrics_json(
      (fs::path(run_dir(full.dir.string(), "worldcentric", 2)) / "metrics.json").string());
  EXPECT_EQ(in_mc.metrics.errors.mean_m, direct.metrics.errors.mean_m);
  EXPECT_EQ(in_mc.metrics.anees, direct.metrics.anees);
  // The dataset handed over in memory gives the methods the very numbers its files give them.
  const fs::path in_memory(run_dir(full.dir.string(), "worldcentric", 2));
  for (const char* file : {"nees.csv", "trajectory.tum", "scans.csv", "matches.csv"}) {
    EXPECT_EQ(read_text(tmp.file(std::string("wc/") + file)),
              read_text((in_memory / file).string()))
        << file;
  }
  EXPECT_EQ(in_mc.metrics.errors.max_m, direct.metrics.errors.max_m);
  EXPECT_EQ(in_mc.metrics.diagnostics, direct.metrics.diagnostics);
}

// --keep-datasets writes each run's dataset beside its results; the run names it, and `run` on it
// gives the same trajectory.
TEST(MonteCarloCommand, KeptDatasetsAreTheRunsOwn) {
  const TempDir tmp;
  MonteCarloOptions options = options_for(tmp.path() / "mc");
  options.runs = 1;
  options.methods = {"worldcentric"};
  options.keep_datasets = true;
  run_montecarlo(options);
  const fs::path dataset = tmp.path() / "mc" / "datasets" / "run_0000";
  EXPECT_TRUE(fs::is_regular_file(dataset / "truth" / "trajectory.tum"));
  EXPECT_TRUE(fs::is_regular_file(dataset / "calibration.yaml"));
  const fs::path rd(run_dir((tmp.path() / "mc").string(), "worldcentric", 0));
  EXPECT_EQ(results::read_metrics_json((rd / "metrics.json").string()).dataset_dir,
            fs::absolute(dataset).lexically_normal().string());
  run({dataset.string(), "worldcentric", tmp.file("again"), ""});
  EXPECT_EQ(read_text(tmp.file("again/trajectory.tum")),
            read_text((rd / "trajectory.tum").string()));
  // Without the flag nothing is kept, and the run names its dataset as held in memory.
  EXPECT_FALSE(fs::exists(full_run().dir / "datasets"));
  EXPECT_EQ(
      results::read_metrics_json(
          (fs::path(run_dir(full_run().dir.string(), "worldcentric", 0)) / "metrics.json").string())
          .dataset_dir,
      "simulated small_basin (seed 1, in memory)");
}

TEST(MonteCarloCommand, ResumeRedoesOnlyTheUnfinishedRun) {
  const TempDir tmp;
  const fs::path dir = tmp.path() / "mc";
  fs::copy(full_run().dir, dir, fs::copy_options::recursive);
  const fs::path redo = fs::path(run_dir(dir.string(), "worldcentric", 1)) / "metrics.json";
  fs::remove(redo);
  auto before = metrics_mtimes(dir);
  const auto logged = run_montecarlo(options_for(dir));
  EXPECT_EQ(logged->outcome.executed, 1u);
  EXPECT_EQ(logged->log.str().rfind("montecarlo: 3/3 runs done", 0), 0u) << logged->log.str();
  auto after = metrics_mtimes(dir);
  ASSERT_TRUE(after.count(redo.string()));
  after.erase(redo.string());
  EXPECT_EQ(after, before);  // deadreckoning's run 1 included: only the missing method reran
  EXPECT_EQ(without_runtimes(read_text((dir / "summary.json").string())),
            without_runtimes(read_text((full_run().dir / "summary.json").string())));
  EXPECT_EQ(read_text((dir / "nees.csv").string()),
            read_text((full_run().dir / "nees.csv").string()));

  // Nothing left to do: nothing runs.
  EXPECT_EQ(run_montecarlo(options_for(dir))->outcome.executed, 0u);
}

TEST(MonteCarloCommand, MergedShardsGiveTheSameSummary) {
  const TempDir tmp;
  const fs::path shard0 = tmp.path() / "shard_0", shard1 = tmp.path() / "shard_1";
  EXPECT_EQ(run_montecarlo(options_for(shard0, "0/2"))->outcome.runs, 2u);
  EXPECT_EQ(run_montecarlo(options_for(shard1, "1/2"))->outcome.runs, 1u);
  EXPECT_EQ(read_text((shard1 / "seeds.csv").string()), "run,seed\n1,2\n");
  const fs::path merged = tmp.path() / "merged";
  const MonteCarloOutcome outcome = merge_montecarlo({merged.string(), {shard0, shard1}});
  EXPECT_EQ(outcome.runs, 3u);
  EXPECT_EQ(outcome.failed, 0u);
  const fs::path full = full_run().dir;
  const std::string summary = read_text((merged / "summary.json").string());
  EXPECT_EQ(without_runtimes(summary),
            without_runtimes(read_text((full / "summary.json").string())));
  EXPECT_NE(summary.find("\"runtime_s\""), std::string::npos);
  for (const char* file : {"nees.csv", "seeds.csv", "scenario.yaml"}) {
    EXPECT_EQ(read_text((merged / file).string()), read_text((full / file).string())) << file;
  }
  for (int r = 0; r < 3; ++r) {
    EXPECT_TRUE(fs::exists(fs::path(run_dir(merged.string(), "worldcentric", r)) / "nees.csv"));
  }

  // Shards of another scenario do not merge.
  const fs::path other = tmp.path() / "other";
  fs::copy(shard1, other, fs::copy_options::recursive);
  write_text((other / "scenario.yaml").string(), "name: other\n");
  EXPECT_THROW(merge_montecarlo({(tmp.path() / "m2").string(), {shard0, other}}), io::InputError);
  EXPECT_THROW(merge_montecarlo({(tmp.path() / "m3").string(), {tmp.path().string()}}),
               io::InputError);
}

// The runs of one directory come from one build: a directory (or a shard) recorded with another
// executable digest is neither resumed nor merged, so results of other defaults never mix.
TEST(MonteCarloCommand, AnotherBuildIsNotResumedOrMerged) {
  const TempDir tmp;
  const std::string digest = executable_digest(self_executable());
  EXPECT_EQ(digest.size(), 16u);
  const std::string manifest = read_text((full_run().dir / "montecarlo.json").string());
  ASSERT_NE(manifest.find("\"executable_digest\": \"" + digest + "\""), std::string::npos)
      << manifest;

  const fs::path dir = tmp.path() / "mc";
  fs::copy(full_run().dir, dir, fs::copy_options::recursive);
  std::string other = manifest;
  other.replace(other.find(digest), digest.size(), "0123456789abcdef");
  write_text((dir / "montecarlo.json").string(), other);
  try {
    run_montecarlo(options_for(dir));
    ADD_FAILURE() << "resumed runs of another build";
  } catch (const io::InputError& e) {
    EXPECT_NE(std::string(e.what()).find("holds runs made by another msislab build (executable "
                                         "digest 0123456789abcdef, this one " +
                                         digest),
              std::string::npos)
        << e.what();
  }
  try {
    merge_montecarlo({(tmp.path() / "merged").string(), {full_run().dir, dir}});
    ADD_FAILURE() << "merged runs of two builds";
  } catch (const io::InputError& e) {
    EXPECT_NE(std::string(e.what()).find("msislab build (executable_digest)"), std::string::npos)
        << e.what();
  }
}

// `msislab ARGS` with MSISLAB_MONTECARLO_FAULTS set (the workers' test hook, docs/cli.md).
testing::CliResult run_with_faults(const std::string& faults, const std::string& args,
                                   const TempDir& tmp) {
  return testing::run_msislab(args, tmp, "env MSISLAB_MONTECARLO_FAULTS=" + faults);
}

// Failed runs are recorded while the others finish; the command writes the whole summary with the
// failures counted and exits 3 (finished, with failed runs) after one line naming the count and
// where the failed.json files are; so does a merge that holds them, but not one whose runs are
// only missing; resumed without the faults, the failed runs are redone and it exits 0.
TEST(MonteCarloCli, FailedRunsAreRecordedTheOthersFinishAndTheExitStatusIs3) {
  const TempDir tmp;
  const fs::path dir = tmp.path() / "mc";
  const std::string args = "montecarlo " + testing::shell_quote(kScenario) +
                           " --runs 3 --methods deadreckoning,worldcentric --jobs 2 --no-plot "
                           "--out " +
                           testing::shell_quote(dir.string());
  // worldcentric throws in run 1; the worker of run 2 crashes (SIGSEGV) while simulating.
  const testing::CliResult failing =
      run_with_faults("1:worldcentric:throw,2:simulate:crash", args, tmp);
  EXPECT_EQ(failing.exit_code, 3) << failing.err;
  EXPECT_NE(failing.out.find("holds 3 runs (3 run now, 0 already done), 2 with a failed method"),
            std::string::npos)
      << failing.out;
  EXPECT_NE(failing.err.find("3/3 runs done, 2 failed"), std::string::npos) << failing.err;
  const std::string last_line =
      "montecarlo: finished, but 2 of 3 runs have a failed method (exit status 3); see " +
      dir.string() + "/runs/*/run_*/failed.json\n";
  ASSERT_GE(failing.err.size(), last_line.size());
  EXPECT_EQ(failing.err.substr(failing.err.size() - last_line.size()), last_line) << failing.err;

  const std::string failed_run =
      read_text((fs::path(run_dir(dir.string(), "worldcentric", 1)) / "failed.json").string());
  EXPECT_NE(failed_run.find("\"reason\": \"injected failure (MSISLAB_MONTECARLO_FAULTS)\""),
            std::string::npos)
      << failed_run;
  EXPECT_NE(failed_run.find("\"stage\": \"run\""), std::string::npos) << failed_run;
  for (const std::string& method : kMethods) {
    const fs::path rd(run_dir(dir.string(), method, 2));
    const std::string killed = read_text((rd / "failed.json").string());
    EXPECT_NE(killed.find("\"reason\": \"killed by signal 11"), std::string::npos) << killed;
    EXPECT_NE(killed.find("\"stage\": \"simulate\""), std::string::npos) << killed;
    EXPECT_NE(killed.find("\"seed\": 3"), std::string::npos) << killed;
    EXPECT_FALSE(fs::exists(rd / "metrics.json"));
    EXPECT_TRUE(fs::exists(fs::path(run_dir(dir.string(), method, 0)) / "metrics.json"));
  }
  EXPECT_TRUE(fs::exists(fs::path(run_dir(dir.string(), "deadreckoning", 1)) / "metrics.json"));
  EXPECT_FALSE(fs::exists(dir / "scratch"));

  const io::Json root = io::read_json_file((dir / "summary.json").string());
  const io::JsonObject summary(root, "summary.json");
  EXPECT_EQ(summary.object("deadreckoning").number("runs"), 2);
  EXPECT_EQ(summary.object("deadreckoning").number("failed"), 1);
  EXPECT_EQ(summary.object("worldcentric").number("runs"), 1);
  EXPECT_EQ(summary.object("worldcentric").number("failed"), 2);
  EXPECT_NE(read_text((dir / "summary.json").string()).find("\"failed_runs\": [1, 2]"),
            std::string::npos);
  EXPECT_TRUE(fs::exists(dir / "nees.csv"));

  // Merged as a shard, the failures come along: exit 3, the merged summary counts them.
  const fs::path merged = tmp.path() / "merged";
  const std::string merge = "montecarlo merge " + testing::shell_quote(merged.string()) + " ";
  const testing::CliResult with_failures =
      testing::run_msislab(merge + testing::shell_quote(dir.string()) + " --no-plot", tmp);
  EXPECT_EQ(with_failures.exit_code, 3) << with_failures.err;
  EXPECT_NE(with_failures.err.find("montecarlo merge: finished, but 2 of 3 runs have a failed "
                                   "method (exit status 3); see " +
                                   merged.string() + "/runs/*/run_*/failed.json"),
            std::string::npos)
      << with_failures.err;
  EXPECT_EQ(without_runtimes(read_text((merged / "summary.json").string())),
            without_runtimes(read_text((dir / "summary.json").string())));
  // Without the failed run directories the shard is merely unfinished: its runs are missing.
  const fs::path unfinished = tmp.path() / "unfinished";
  fs::copy(dir, unfinished, fs::copy_options::recursive);
  fs::remove_all(run_dir(unfinished.string(), "worldcentric", 1));
  for (const std::string& method : kMethods)
    fs::remove_all(run_dir(unfinished.string(), method, 2));
  const fs::path partial = tmp.path() / "partial";
  const testing::CliResult missing =
      testing::run_msislab("montecarlo merge " + testing::shell_quote(partial.string()) + " " +
                               testing::shell_quote(unfinished.string()) + " --no-plot",
                           tmp);
  EXPECT_EQ(missing.exit_code, 0) << missing.err;
  const io::Json partial_root = io::read_json_file((partial / "summary.json").string());
  const io::JsonObject partial_summary(partial_root, "summary.json");
  EXPECT_EQ(partial_summary.object("worldcentric").number("failed"), 0);
  EXPECT_EQ(partial_summary.object("worldcentric").number("missing"), 2);

  // Resumed once the failures stop, the failed runs are redone and the summary is the full one.
  const testing::CliResult resumed = testing::run_msislab(args, tmp);
  EXPECT_EQ(resumed.exit_code, 0) << resumed.err;
  EXPECT_NE(resumed.out.find("(2 run now, 1 already done), 0 with a failed method"),
            std::string::npos)
      << resumed.out;
  EXPECT_EQ(resumed.err.find("finished, but"), std::string::npos) << resumed.err;
  EXPECT_FALSE(fs::exists(fs::path(run_dir(dir.string(), "worldcentric", 1)) / "failed.json"));
  EXPECT_EQ(without_runtimes(read_text((dir / "summary.json").string())),
            without_runtimes(read_text((full_run().dir / "summary.json").string())));
}

// Expects montecarlo() to throw InputError containing `word` without creating the directory.
void expect_rejected(const MonteCarloOptions& options, const std::string& word) {
  std::ostringstream log;
  try {
    montecarlo(options, {log, false});
    ADD_FAILURE() << "no InputError for " << word;
  } catch (const io::InputError& e) {
    EXPECT_NE(std::string(e.what()).find(word), std::string::npos) << e.what();
  }
  EXPECT_FALSE(fs::exists(options.out_dir)) << word;
}

TEST(MonteCarloCommand, BadInputIsRejectedBeforeAnythingRuns) {
  const TempDir tmp;
  const fs::path out = tmp.path() / "mc";
  MonteCarloOptions options = options_for(out);
  options.methods = {"deadreckoning", "nosuchmethod"};
  expect_rejected(options, "available: robocentric");
  options.methods = {"worldcentric", "worldcentric"};
  expect_rejected(options, "given twice");
  for (const char* shard : {"2/2", "x", "1/0"}) {
    expect_rejected(options_for(out, shard), std::string("--shard '") + shard + "'");
  }
  options = options_for(out);
  options.scenario_path = tmp.file("missing.yaml");
  expect_rejected(options, tmp.file("missing.yaml"));
  options = options_for(out);
  options.runs = 0;
  expect_rejected(options, "--runs 0");
  options = options_for(out);
  options.config_path = write_text(tmp.file("bad.yaml"), "segmentz: {}\n");
  expect_rejected(options, "segmentz");

  // A directory made from another scenario is not resumed.
  const fs::path used = tmp.path() / "used";
  fs::copy(full_run().dir, used, fs::copy_options::recursive);
  write_text((used / "scenario.yaml").string(), "name: another\n");
  try {
    montecarlo(options_for(used), {std::cerr, false});
    ADD_FAILURE() << "resumed a directory of another scenario";
  } catch (const io::InputError& e) {
    EXPECT_NE(std::string(e.what()).find("another scenario"), std::string::npos) << e.what();
  }
}

/// Starts msislab with the arguments in the background, stdout and stderr into files; its pid.
pid_t start_msislab(const std::vector<std::string>& args, const TempDir& tmp) {
  const pid_t pid = ::fork();
  if (pid == 0) {
    const int out = ::open(tmp.file("bg.out").c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
    const int err = ::open(tmp.file("bg.err").c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
    ::dup2(out, STDOUT_FILENO);
    ::dup2(err, STDERR_FILENO);
    std::vector<char*> argv;
    argv.push_back(const_cast<char*>(MSISLAB_EXE));
    for (const std::string& a : args) argv.push_back(const_cast<char*>(a.c_str()));
    argv.push_back(nullptr);
    ::execv(MSISLAB_EXE, argv.data());
    ::_exit(127);
  }
  return pid;
}

/// The processes whose command line mentions `text` (the Monte Carlo directory: the command and
/// its workers, which are forks of it).
std::vector<std::string> processes_mentioning(const std::string& text) {
  std::vector<std::string> found;
  for (const auto& entry : fs::directory_iterator("/proc")) {
    const std::string name = entry.path().filename().string();
    if (name.find_first_not_of("0123456789") != std::string::npos) continue;
    std::ifstream in(entry.path() / "cmdline", std::ios::binary);
    std::string cmdline((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    std::replace(cmdline.begin(), cmdline.end(), '\0', ' ');
    if (cmdline.find(text) != std::string::npos) found.push_back(name + ": " + cmdline);
  }
  return found;
}

/// Waits until the file exists; false after the timeout.
bool wait_for_file(const fs::path& file, std::chrono::seconds timeout) {
  const auto end = std::chrono::steady_clock::now() + timeout;
  while (!fs::exists(file)) {
    if (std::chrono::steady_clock::now() > end) return false;
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  }
  return true;
}

// One writer per directory, and a clean stop: while a sweep runs (40 runs, long enough that it
// is still running when its first run is in, the scenario traced once) a second command on its
// directory exits 2 naming the holder; SIGTERM ends it and every worker (exit 143), keeps the
// finished runs and leaves nothing half-written; the same command then completes the sweep with
// the summary and NEES of an uninterrupted one (byte for byte, the wall times apart).
TEST(MonteCarloCli, SigtermStopsEveryWorkerAndTheRerunCompletesTheSweep) {
  const TempDir tmp;
  const std::string out = tmp.file("mc_stopped");
  const std::vector<std::string> args = {
      "montecarlo", kScenario, "--runs",    "40",    "--methods", "deadreckoning,worldcentric",
      "--jobs",     "2",       "--no-plot", "--out", out};
  const pid_t pid = start_msislab(args, tmp);
  ASSERT_GT(pid, 0);
  ASSERT_TRUE(wait_for_file(fs::path(run_dir(out, "worldcentric", 0)) / "metrics.json",
                            std::chrono::seconds(60)));

  const std::string second = "montecarlo " + testing::shell_quote(kScenario) +
                             " --runs 40 --methods deadreckoning,worldcentric --no-plot --out " +
                             testing::shell_quote(out);
  const testing::CliResult refused = testing::run_msislab(second, tmp);
  EXPECT_EQ(refused.exit_code, 2) << refused.err;
  EXPECT_EQ(std::count(refused.err.begin(), refused.err.end(), '\n'), 1) << refused.err;
  EXPECT_NE(refused.err.find(out + ": in use by another msislab command (msislab montecarlo "),
            std::string::npos)
      << refused.err;
  EXPECT_NE(refused.err.find("pid " + std::to_string(pid)), std::string::npos) << refused.err;

  ASSERT_EQ(::kill(pid, SIGTERM), 0);
  int status = 0;
  ASSERT_EQ(::waitpid(pid, &status, 0), pid);
  const std::string err = read_text(tmp.file("bg.err"));
  ASSERT_TRUE(WIFEXITED(status)) << err;
  if (WEXITSTATUS(status) == 0) GTEST_SKIP() << "the sweep finished before SIGTERM arrived";
  EXPECT_EQ(WEXITSTATUS(status), 128 + SIGTERM) << err;
  EXPECT_NE(err.find("montecarlo: stopped by TERM"), std::string::npos) << err;
  EXPECT_EQ(processes_mentioning(out), std::vector<std::string>{});
  EXPECT_FALSE(fs::exists(fs::path(out) / "scratch"));
  EXPECT_FALSE(fs::exists(fs::path(out) / "summary.json"));
  int finished = 0;
  for (const auto& entry : fs::recursive_directory_iterator(fs::path(out) / "runs")) {
    const std::string name = entry.path().filename().string();
    EXPECT_EQ(name.find(".partial"), std::string::npos) << entry.path();
    if (name.rfind("run_", 0) == 0) {
      // A run directory is whole: its result files, or a recorded failure.
      EXPECT_TRUE(fs::exists(entry.path() / "metrics.json")) << entry.path();
      EXPECT_TRUE(fs::exists(entry.path() / "errors.csv")) << entry.path();
      ++finished;
    }
  }
  EXPECT_GE(finished, 1);
  EXPECT_LT(finished, 80);

  // The same command resumes and completes; an uninterrupted sweep gives the same numbers.
  const testing::CliResult resumed = testing::run_msislab(second, tmp);
  ASSERT_EQ(resumed.exit_code, 0) << resumed.err;
  EXPECT_NE(resumed.out.find("holds 40 runs ("), std::string::npos) << resumed.out;
  const std::string whole = tmp.file("mc_whole");
  const testing::CliResult uninterrupted = testing::run_msislab(
      "montecarlo " + testing::shell_quote(kScenario) +
          " --runs 40 --methods deadreckoning,worldcentric --jobs 1 --no-plot --out " +
          testing::shell_quote(whole),
      tmp);
  ASSERT_EQ(uninterrupted.exit_code, 0) << uninterrupted.err;
  EXPECT_EQ(without_runtimes(read_text(out + "/summary.json")),
            without_runtimes(read_text(whole + "/summary.json")));
  for (const char* file : {"nees.csv", "errors.csv", "error_histogram.csv", "seeds.csv"}) {
    EXPECT_EQ(read_text(out + "/" + file), read_text(whole + "/" + file)) << file;
  }
}

// Through the executable: the child processes are /proc/self/exe; bad arguments exit 2 with one
// line.
TEST(MonteCarloCli, RunsThroughTheExecutableAndRejectsBadArguments) {
  const TempDir tmp;
  const std::string out = tmp.file("mc");
  const std::string args = "montecarlo " + testing::shell_quote(kScenario) +
                           " --runs 2 --methods deadreckoning --jobs 2 --out " +
                           testing::shell_quote(out);
  const testing::CliResult ok = testing::run_msislab(args, tmp);
  EXPECT_EQ(ok.exit_code, 0) << ok.err;
  EXPECT_NE(ok.out.find("holds 2 runs (2 run now, 0 already done), 0 with a failed method"),
            std::string::npos)
      << ok.out;
  EXPECT_NE(ok.err.find("montecarlo: 2/2 runs done, 0 failed, elapsed "), std::string::npos)
      << ok.err;
  EXPECT_TRUE(fs::exists(fs::path(out) / "runs/deadreckoning/run_0001/metrics.json"));
  // The figure, drawn by `msislab plot` in a child process (under xvfb-run without a display);
  // where neither is available the run still succeeds and says so on stderr.
  const bool can_draw =
      std::getenv("DISPLAY") != nullptr ||
      std::system("command -v xvfb-run >/dev/null && command -v xauth >/dev/null") == 0;
  if (can_draw) {
    for (const char* figure : {"nees.png", "error_spread.png", "error_distribution.png"}) {
      EXPECT_TRUE(fs::is_regular_file(fs::path(out) / "figures" / figure)) << ok.err;
      EXPECT_NE(ok.out.find("montecarlo: wrote " + out + "/figures/" + figure), std::string::npos)
          << ok.out;
    }
  } else {
    EXPECT_NE(ok.err.find("montecarlo: figures not drawn ("), std::string::npos) << ok.err;
  }
  EXPECT_FALSE(fs::exists(fs::path(out) / ".plot_stderr.txt"));
  // Resumed with --no-plot: nothing to run, no figure drawn.
  fs::remove_all(fs::path(out) / "figures");
  const testing::CliResult again = testing::run_msislab(args + " --no-plot", tmp);
  EXPECT_EQ(again.exit_code, 0) << again.err;
  EXPECT_NE(again.out.find("(0 run now, 2 already done)"), std::string::npos) << again.out;
  EXPECT_FALSE(fs::exists(fs::path(out) / "figures"));

  const std::string scenario = testing::shell_quote(kScenario);
  for (const std::string& bad : std::vector<std::string>{
           "montecarlo " + scenario + " --runs 2 --out o --methods deadreckoning,bogus",
           "montecarlo " + scenario + " --runs 2 --out o --methods deadreckoning --shard 3/2",
           "montecarlo " + scenario + " --runs two --out o --methods deadreckoning",
           "montecarlo " + scenario + " --out o --methods deadreckoning",
           std::string("montecarlo no_such.yaml --runs 2 --out o --methods deadreckoning"),
           "montecarlo merge o " + testing::shell_quote(tmp.path().string())}) {
    const testing::CliResult result = testing::run_msislab(bad, tmp);
    EXPECT_EQ(result.exit_code, 2) << bad;
    EXPECT_EQ(std::count(result.err.begin(), result.err.end(), '\n'), 1) << bad << result.err;
    EXPECT_EQ(result.err.rfind("msislab: ", 0), 0u) << result.err;
  }
}

}  // namespace
}  // namespace msislab::app
