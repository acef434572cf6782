// External methods (a methods file, docs/formats.md) end to end through the msislab executable:
// the example (examples/external_method, mydr) in a 2-run Monte Carlo of small_basin beside dead
// reckoning, in the report and on the real St. Pere data; programs that fail in every way one can
// (non-zero exit, past the time limit, a malformed or empty trajectory, a trajectory written
// outside {out} and linked in) each recorded as that method's failure; the example in a sweep; bad
// methods files; and no program left alive after msislab is stopped.
#include <fcntl.h>
#include <gtest/gtest.h>
#include <signal.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <string>
#include <thread>

#include "cli_runner.hpp"
#include "io/json.hpp"
#include "results/sweep_files.hpp"
#include "settings/config_yaml.hpp"
#include "stats/chi_square.hpp"
#include "test_support.hpp"

extern char** environ;

namespace msislab::testing {
namespace {

namespace fs = std::filesystem;

const std::string kSource = MSISLAB_SOURCE_DIR;
const std::string kScenario = kSource + "/scenarios/small_basin.yaml";
const std::string kExample = kSource + "/examples/external_method/methods.yaml";

/// A small simulated dataset, made once.
const std::string& dataset() {
  static const TempDir tmp;
  static const std::string dir = [] {
    const std::string out = tmp.file("basin");
    const CliResult r = run_msislab(
        "simulate " + shell_quote(kScenario) + " --out " + shell_quote(out) + " --threads 2", tmp);
    EXPECT_EQ(r.exit_code, 0) << r.err;
    return out;
  }();
  return dir;
}

/// The misbehaving programs, as shell scripts of a methods file in `tmp` (marker: a unique word
/// on the hanging program's command line, for pgrep).
std::string bad_methods(const TempDir& tmp, const std::string& marker) {
  write_text(tmp.file("fails.sh"), "echo 'line one' >&2\necho 'it went wrong' >&2\nexit 3\n");
  write_text(tmp.file("malformed.sh"), "printf '1 2 3\\n' > trajectory.tum\n");
  write_text(tmp.file("empty.sh"), ": > \"$1/trajectory.tum\"\n");
  // Writes a good trajectory outside {out} and links it in: never read.
  write_text(tmp.file("outside.sh"),
             "cp \"$2/truth/trajectory.tum\" \"$1/../stolen.tum\"\n"
             "ln -s \"$1/../stolen.tum\" \"$1/trajectory.tum\"\n");
  return write_text(
      tmp.file("bad.yaml"),
      "methods:\n"
      "  - {name: fails, command: [sh, '{methods_dir}/fails.sh'], time_limit_s: 30}\n"
      "  - name: hangs\n"
      "    command: [sh, -c, 'sleep 60 & sleep 60; : " +
          marker +
          "']\n"
          "    time_limit_s: 1\n"
          "  - {name: malformed, command: [sh, '{methods_dir}/malformed.sh'], time_limit_s: 30}\n"
          "  - {name: empty, command: [sh, '{methods_dir}/empty.sh', '{out}'], time_limit_s: 30}\n"
          "  - name: outside\n"
          "    command: [sh, '{methods_dir}/outside.sh', '{out}', '{dataset}']\n"
          "    time_limit_s: 30\n");
}

/// Whether a process with the marker on its command line runs ("[m]arker": the shell running
/// pgrep, whose command line holds the pattern, does not match it).
/// How many processes have the marker in their command line.
int alive_count(const std::string& marker) {
  const std::string pattern = "[" + marker.substr(0, 1) + "]" + marker.substr(1);
  FILE* pgrep = ::popen(("pgrep -c -f " + shell_quote(pattern)).c_str(), "r");
  int count = 0;
  if (pgrep == nullptr || std::fscanf(pgrep, "%d", &count) != 1) count = 0;
  if (pgrep != nullptr) ::pclose(pgrep);
  return count;
}

bool alive(const std::string& marker) { return alive_count(marker) > 0; }

io::Json read_json(const fs::path& path) { return io::Json::parse(read_text(path.string())); }

TEST(ExternalMethod, ExampleInMonteCarloBesideDeadReckoningAndInTheReport) {
  const TempDir tmp;
  const fs::path mc = tmp.path() / "mc";
  const std::string common = "montecarlo " + shell_quote(kScenario) +
                             " --runs 2 --jobs 2 --methods deadreckoning,mydr --methods-file " +
                             shell_quote(kExample);
  const CliResult r = run_msislab(common + " --out " + shell_quote(mc.string()), tmp);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const io::Json summary = read_json(mc / "summary.json");
  const io::Json& mydr = summary.at("mydr");
  EXPECT_EQ(mydr.at("runs").get<int>(), 2);
  const double error_m = mydr.at("mean_error_m").get<double>();
  const double anees = mydr.at("anees").get<double>();
  std::printf("mydr on small_basin, 2 runs: mean error %.3f m, ANEES %.3f\n", error_m, anees);
  EXPECT_GT(error_m, 0.0);
  EXPECT_LT(error_m, 5.0);
  // The example's covariance is consistent on the basin: its ANEES inside the two-sided 95 %
  // chi-square bounds of the average over 2 runs ([0.62, 7.22]; each run's scans taken as one
  // variable, the widest case, since a run's scans share their errors).
  const auto [lower, upper] = average_chi2_bounds(2, 3, 0.05);
  EXPECT_GE(anees, lower);
  EXPECT_LE(anees, upper);
  EXPECT_EQ(mydr.at("paired_difference").at("reference").get<std::string>(), "deadreckoning");
  EXPECT_EQ(mydr.at("paired_difference").at("runs").get<int>(), 2);
  EXPECT_TRUE(fs::exists(mc / "methods.yaml"));
  EXPECT_FALSE(fs::exists(mc / "scratch")) << "the scratch dataset is removed after its run";
  // The same seeds give the same bytes: a second directory.
  const fs::path again = tmp.path() / "again";
  ASSERT_EQ(run_msislab(common + " --no-plot --out " + shell_quote(again.string()), tmp).exit_code,
            0);
  EXPECT_EQ(read_text((mc / "runs/mydr/run_0001/nees.csv").string()),
            read_text((again / "runs/mydr/run_0001/nees.csv").string()));
  // Resuming with another methods file is refused.
  const std::string other = write_text(tmp.file("other.yaml"), read_text(kExample) + "\n# x\n");
  const CliResult refused =
      run_msislab("montecarlo " + shell_quote(kScenario) +
                      " --runs 2 --methods deadreckoning,mydr --methods-file " +
                      shell_quote(other) + " --out " + shell_quote(mc.string()),
                  tmp);
  EXPECT_EQ(refused.exit_code, 2);
  EXPECT_NE(refused.err.find("another methods file"), std::string::npos) << refused.err;
  // The report lists it beside dead reckoning, under its title.
  ASSERT_TRUE(fs::exists(mc / "figures" / "nees.png")) << r.err;
  const std::string page = tmp.file("page.md");
  const CliResult report =
      run_msislab("report " + shell_quote(page) + " --montecarlo " + shell_quote(mc.string()) +
                      " --methods-file " + shell_quote(kExample),
                  tmp);
  ASSERT_EQ(report.exit_code, 0) << report.err;
  const std::string md = read_text(page);
  EXPECT_NE(md.find("Python dead reckoning"), std::string::npos);
  EXPECT_NE(md.find("Dead reckoning"), std::string::npos);
}

TEST(ExternalMethod, ARelativeOutWorksInMonteCarlo) {
  // {out} is absolute whatever --out was: the example, run in its own folder, writes there.
  const TempDir tmp;
  const CliResult r =
      run_shell("cd " + shell_quote(tmp.path().string()) + " && " + shell_quote(MSISLAB_EXE) +
                    " montecarlo " + shell_quote(kScenario) +
                    " --runs 1 --methods mydr --no-plot --out mc_ext "
                    "--methods-file " +
                    shell_quote(kExample),
                tmp);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(read_json(tmp.path() / "mc_ext" / "summary.json").at("mydr").at("runs").get<int>(), 1);
}

TEST(ExternalMethod, ItsConfigHoldsTheNoiseTheRunTookFromTheDataset) {
  // A --config saying `navigation_noise: dataset`: the program's {config} holds the noise the run
  // took from the dataset's navigation_noise.yaml (in a Monte Carlo, the scenario's), its own keys
  // kept, and says `navigation_noise: config`; not the bare key the program cannot resolve. The
  // program keeps a copy of what it was given and hands back the truth as its trajectory.
  const TempDir tmp;
  write_text(tmp.file("sees.sh"),
             "cp \"$3\" \"$4\"\ncp \"$2/truth/trajectory.tum\" \"$1/trajectory.tum\"\n");
  const std::string seen = tmp.file("seen.yaml");
  const std::string methods = write_text(
      tmp.file("sees.yaml"),
      "methods:\n  - name: sees\n    command: [sh, '{methods_dir}/sees.sh', '{out}', '{dataset}', "
      "'{config}', '" +
          seen + "']\n    time_limit_s: 30\n");
  const std::string config =
      write_text(tmp.file("config.yaml"),
                 "navigation_noise: dataset\ndead_reckoning:\n  accel_sigma_mps2: 0.3\n");
  const NavigationNoise noise =
      settings::read_navigation_noise((fs::path(dataset()) / "navigation_noise.yaml").string());
  const auto expect_resolved = [&](const std::string& where) {
    SCOPED_TRACE(where);
    const std::string text = read_text(seen);
    EXPECT_NE(text.find("navigation_noise: config"), std::string::npos) << text;
    const SlamConfig given = settings::read_slam_config(seen);
    EXPECT_FALSE(given.navigation_noise_from_dataset);
    EXPECT_DOUBLE_EQ(given.dead_reckoning.dvl_sigma_mps, noise.dvl_sigma_mps);
    EXPECT_DOUBLE_EQ(given.dead_reckoning.heading_sigma_rad, noise.heading_sigma_deg * M_PI / 180);
    EXPECT_DOUBLE_EQ(given.dead_reckoning.heading_bias_walk_deg_per_sqrt_s,
                     noise.heading_bias_walk_deg_per_sqrt_s);
    EXPECT_DOUBLE_EQ(given.dead_reckoning.accel_sigma_mps2, 0.3);  // the file's own
    fs::remove(seen);
  };
  const CliResult run = run_msislab("run " + shell_quote(dataset()) + " --method sees --out " +
                                        shell_quote(tmp.file("run")) + " --methods-file " +
                                        shell_quote(methods) + " --config " + shell_quote(config),
                                    tmp);
  ASSERT_EQ(run.exit_code, 0) << run.err;
  expect_resolved("run");
  const CliResult mc = run_msislab("montecarlo " + shell_quote(kScenario) +
                                       " --runs 1 --methods sees --no-plot --out " +
                                       shell_quote(tmp.file("mc")) + " --methods-file " +
                                       shell_quote(methods) + " --config " + shell_quote(config),
                                   tmp);
  ASSERT_EQ(mc.exit_code, 0) << mc.err;
  expect_resolved("montecarlo");
}

TEST(ExternalMethod, ExampleInASweepRunsOnEachCellsOwnData) {
  // Two cells that differ in the MRU's heading noise: the program reads each cell's own logs (its
  // error differs between them, as the built-in dead reckoning's does), scored per cell.
  const TempDir tmp;
  const std::string sweep_file =
      write_text(tmp.file("sweep.yaml"), "scenario: " + kScenario +
                                             "\n"
                                             "runs: 2\n"
                                             "methods: [deadreckoning, mydr]\n"
                                             "grid:\n"
                                             "  scenario.mru.heading_noise_deg: [0.1, 5]\n");
  const fs::path out = tmp.path() / "sweep";
  const CliResult r =
      run_msislab("sweep " + shell_quote(sweep_file) + " --jobs 2 --no-plot --methods-file " +
                      shell_quote(kExample) + " --out " + shell_quote(out.string()),
                  tmp);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const results::SweepTable table = results::read_sweep_csv((out / "sweep.csv").string());
  ASSERT_EQ(table.rows.size(), 4u);  // 2 cells x 2 methods
  std::vector<double> mydr_m, dr_m;
  for (const results::SweepRow& row : table.rows) {
    EXPECT_EQ(row.runs, 2) << row.method;
    EXPECT_EQ(row.failed, 0) << row.method;
    ASSERT_TRUE(row.mean_error_m.has_value()) << row.method;
    (row.method == "mydr" ? mydr_m : dr_m).push_back(*row.mean_error_m);
    if (row.method == "mydr") {
      EXPECT_EQ(row.paired_reference, "deadreckoning");
    }
  }
  ASSERT_EQ(mydr_m.size(), 2u);
  std::printf(
      "sweep, heading noise 0.1 / 5 deg: mydr %.3f / %.3f m, dead reckoning %.3f / %.3f m\n",
      mydr_m[0], mydr_m[1], dr_m[0], dr_m[1]);
  EXPECT_NE(mydr_m[0], mydr_m[1]) << "the program saw the same data in both cells";
  for (const char* cell : {"cell_000", "cell_001"}) {
    EXPECT_TRUE(fs::exists(out / "cells" / cell / "runs/mydr/run_0001/trajectory.tum")) << cell;
    EXPECT_FALSE(fs::exists(out / "cells" / cell / "scratch")) << cell;
  }
}

TEST(ExternalMethod, EachFailureIsRecordedForItsMethodAlone) {
  const TempDir tmp;
  const std::string marker = "msislab_hang_marker_" + std::to_string(::getpid());
  const std::string methods = bad_methods(tmp, marker);
  const fs::path mc = tmp.path() / "mc";
  const CliResult r = run_msislab(
      "montecarlo " + shell_quote(kScenario) +
          " --runs 1 --no-plot --methods deadreckoning,fails,hangs,malformed,empty,outside "
          "--methods-file " +
          shell_quote(methods) + " --out " + shell_quote(mc.string()),
      tmp);
  // Finished with failed runs: the summary is written and the status says so (docs/cli.md).
  ASSERT_EQ(r.exit_code, 3) << r.err;
  EXPECT_NE(r.err.find("montecarlo: finished, but 1 of 1 runs have a failed method"),
            std::string::npos)
      << r.err;
  EXPECT_TRUE(fs::exists(mc / "runs/deadreckoning/run_0000/metrics.json"));
  const auto failure = [&](const std::string& method) {
    const fs::path file = mc / "runs" / method / "run_0000" / "failed.json";
    EXPECT_TRUE(fs::exists(file)) << method;
    EXPECT_FALSE(fs::exists(file.parent_path() / "metrics.json")) << method;
    return fs::exists(file) ? read_json(file) : io::Json::object();
  };
  const io::Json fails = failure("fails");
  EXPECT_EQ(fails.at("reason").get<std::string>(), "exit status 3");
  EXPECT_EQ(fails.at("stderr").size(), 2u);
  EXPECT_EQ(fails.at("stderr").back().get<std::string>(), "it went wrong");
  EXPECT_NE(failure("hangs").at("reason").get<std::string>().find("time limit of 1 s exceeded"),
            std::string::npos);
  EXPECT_FALSE(alive(marker)) << "the hanging program's group outlived its time limit";
  EXPECT_NE(failure("malformed").at("reason").get<std::string>().find("trajectory.tum:1"),
            std::string::npos);
  EXPECT_NE(failure("empty").at("reason").get<std::string>().find("no data rows"),
            std::string::npos);
  EXPECT_NE(failure("outside").at("reason").get<std::string>().find("not a regular file"),
            std::string::npos);
  const io::Json summary = read_json(mc / "summary.json");
  EXPECT_EQ(summary.at("deadreckoning").at("runs").get<int>(), 1);
  EXPECT_EQ(summary.at("fails").at("failed").get<int>(), 1);

  // In `run`: a clear message with the program's last lines, exit status 1, nothing written.
  const fs::path out = tmp.path() / "run";
  const CliResult run =
      run_msislab("run " + shell_quote(dataset()) + " --method fails --methods-file " +
                      shell_quote(methods) + " --out " + shell_quote(out.string()),
                  tmp);
  EXPECT_EQ(run.exit_code, 1);
  EXPECT_NE(run.err.find("method 'fails' failed: exit status 3"), std::string::npos) << run.err;
  EXPECT_NE(run.err.find("  it went wrong"), std::string::npos) << run.err;
  EXPECT_FALSE(fs::exists(out));
  for (const auto& entry : fs::directory_iterator(tmp.path())) {
    EXPECT_EQ(entry.path().filename().string().find(".external-"), std::string::npos);
  }
}

TEST(ExternalMethod, BadMethodsFilesExit2NamingFileAndKey) {
  const TempDir tmp;
  const auto rejected = [&](const std::string& yaml, const std::string& expected) {
    const std::string file = write_text(tmp.file("methods.yaml"), yaml);
    const fs::path out = tmp.path() / "out";
    const CliResult r =
        run_msislab("run " + shell_quote(dataset()) + " --method x --methods-file " +
                        shell_quote(file) + " --out " + shell_quote(out.string()),
                    tmp);
    EXPECT_EQ(r.exit_code, 2) << yaml;
    EXPECT_NE(r.err.find(file), std::string::npos) << r.err;
    EXPECT_NE(r.err.find(expected), std::string::npos) << r.err;
    EXPECT_FALSE(fs::exists(out));
  };
  rejected("methods:\n  - {name: x, command: [a], time_limit_s: 1, colour_: '#000000'}\n",
           ":2: key 'methods[0].colour_': unknown key");
  rejected("methods:\n  - {name: x, time_limit_s: 1}\n", "key 'methods[0].command': required");
  rejected("methods:\n  - {name: x, command: ['{data}'], time_limit_s: 1}\n",
           "unknown placeholder {data}");
  rejected("methods:\n  - {name: robocentric, command: [a], time_limit_s: 1}\n",
           "'robocentric' is a built-in method");
  rejected("methods:\n  - {name: x, command: [a], time_limit_s: 0}\n",
           "key 'methods[0].time_limit_s': must be > 0");
  rejected("method:\n  - {name: x, command: [a], time_limit_s: 1}\n", "key 'method'");
}

TEST(ExternalMethod, SigtermOfMontecarloLeavesNoProgramAlive) {
  const TempDir tmp;
  const std::string marker = "msislab_sigterm_marker_" + std::to_string(::getpid());
  const std::string methods =
      write_text(tmp.file("slow.yaml"),
                 "methods:\n  - name: slow\n    command: [sh, -c, \"sh -c 'sleep 120; : " + marker +
                     "' & sleep 120; : " + marker + "\"]\n    time_limit_s: 600\n");
  const std::string mc = tmp.file("mc");
  const std::vector<std::string> args = {MSISLAB_EXE, "montecarlo", kScenario, "--runs",
                                         "1",         "--methods",  "slow",    "--methods-file",
                                         methods,     "--no-plot",  "--out",   mc};
  std::vector<char*> argv;
  for (const std::string& a : args) argv.push_back(const_cast<char*>(a.c_str()));
  argv.push_back(nullptr);
  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  posix_spawn_file_actions_addopen(&actions, STDERR_FILENO, tmp.file("err.txt").c_str(),
                                   O_WRONLY | O_CREAT | O_TRUNC, 0644);
  pid_t pid = 0;
  ASSERT_EQ(posix_spawn(&pid, argv[0], &actions, nullptr, argv.data(), environ), 0);
  posix_spawn_file_actions_destroy(&actions);
  const auto until = std::chrono::steady_clock::now() + std::chrono::seconds(60);
  // The program and the child it left in the background, both carrying the marker.
  while (alive_count(marker) < 2 && std::chrono::steady_clock::now() < until) {
    std::this_thread::sleep_for(std::chrono::milliseconds(100));
  }
  ASSERT_GE(alive_count(marker), 2) << "the program and its child never started";
  ::kill(pid, SIGTERM);
  int status = 0;
  ASSERT_EQ(::waitpid(pid, &status, 0), pid);
  ASSERT_TRUE(WIFEXITED(status)) << read_text(tmp.file("err.txt"));
  EXPECT_EQ(WEXITSTATUS(status), 128 + SIGTERM);
  EXPECT_FALSE(alive(marker)) << "a process of the external program outlived msislab";
  EXPECT_FALSE(fs::exists(fs::path(mc) / "runs/slow/run_0000"));
}

TEST(ExternalMethod, ExampleOnTheRealDataIsScoredAgainstGps) {
  MSISLAB_REQUIRE_STPERE();
  const TempDir tmp;
  const fs::path out = tmp.path() / "mydr";
  const CliResult r =
      run_msislab("run " + shell_quote(stpere_dir()) + " --method mydr --methods-file " +
                      shell_quote(kExample) + " --out " + shell_quote(out.string()),
                  tmp);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const io::Json metrics = read_json(out / "metrics.json");
  EXPECT_EQ(metrics.at("method").get<std::string>(), "mydr");
  EXPECT_EQ(metrics.at("truth").get<std::string>(), "gps");
  const double error_m = metrics.at("mean_error_m").get<double>();
  std::printf("mydr on St. Pere: mean error %.3f m against GPS\n", error_m);
  // Plain DVL integration drifts to about 3.8 m (../shared/datasets/stpere/README.md).
  EXPECT_GT(error_m, 2.0);
  EXPECT_LT(error_m, 6.0);
  EXPECT_EQ(metrics.at("scans").get<int>(), 242);
}

}  // namespace
}  // namespace msislab::testing
