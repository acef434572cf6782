// The msislab executable as a user runs it: help, exit status 0 on success and 2 on bad input,
// with exactly one stderr line "msislab: ..." naming the file and line (docs/interfaces.md).
#include <gtest/gtest.h>
#include <sys/wait.h>

#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <string>

#include "cli_runner.hpp"
#include "synthetic_dataset.hpp"
#include "test_support.hpp"

namespace msislab {
namespace {

namespace fs = std::filesystem;
using testing::read_text;
using testing::TempDir;

using testing::CliResult;
using testing::run_msislab;
using testing::shell_quote;

// Exactly one line on stderr, starting "msislab: ".
void expect_one_error_line(const CliResult& result) {
  EXPECT_EQ(std::count(result.err.begin(), result.err.end(), '\n'), 1) << result.err;
  EXPECT_FALSE(result.err.empty() || result.err.back() != '\n') << result.err;
  EXPECT_EQ(result.err.rfind("msislab: ", 0), 0u) << result.err;
}

TEST(Cli, HelpListsTheRunCommand) {
  const TempDir tmp;
  const CliResult result = run_msislab("--help", tmp);
  EXPECT_EQ(result.exit_code, 0) << result.err;
  EXPECT_NE(result.out.find("run"), std::string::npos) << result.out;
}

TEST(Cli, VersionIsTheProjectsVersion) {
  // MSISLAB_VERSION comes from project(VERSION) in CMakeLists.txt, for the executable and here.
  const TempDir tmp;
  const CliResult r = run_msislab("--version", tmp);
  EXPECT_EQ(r.exit_code, 0);
  EXPECT_EQ(r.out, std::string("msislab ") + MSISLAB_VERSION + "\n");
}

TEST(Cli, RunHelpDescribesItsOptions) {
  const TempDir tmp;
  const CliResult result = run_msislab("run --help", tmp);
  EXPECT_EQ(result.exit_code, 0) << result.err;
  for (const char* option : {"--method", "--out", "--config", "DATASET_DIR"}) {
    EXPECT_NE(result.out.find(option), std::string::npos) << option << "\n" << result.out;
  }
}

TEST(Cli, NoArgumentsIsBadInput) {
  const TempDir tmp;
  const CliResult result = run_msislab("", tmp);
  EXPECT_EQ(result.exit_code, 2);
  expect_one_error_line(result);
}

TEST(Cli, UnknownOptionIsBadInput) {
  const TempDir tmp;
  const CliResult result = run_msislab(
      "run " + shell_quote(tmp.file("d")) + " --method deadreckoning --out o --frobnicate 3", tmp);
  EXPECT_EQ(result.exit_code, 2);
  expect_one_error_line(result);
  EXPECT_NE(result.err.find("frobnicate"), std::string::npos) << result.err;
}

TEST(Cli, AMisspeltCommandIsNamedWithTheNearest) {
  // Also with --help after it: an error, not the main help with status 0.
  const TempDir tmp;
  for (const std::string args : {"simulat scenarios/x.yaml --out o", "simulat --help"}) {
    const CliResult result = run_msislab(args, tmp);
    EXPECT_EQ(result.exit_code, 2) << args;
    expect_one_error_line(result);
    EXPECT_NE(result.err.find("unknown command 'simulat' (did you mean 'simulate'?"),
              std::string::npos)
        << result.err;
  }
  const CliResult montecarlo = run_msislab("montecralo", tmp);
  EXPECT_NE(montecarlo.err.find("did you mean 'montecarlo'?"), std::string::npos) << montecarlo.err;
  // Nothing near: named without a guess.
  const CliResult far = run_msislab("xyzzy", tmp);
  EXPECT_EQ(far.exit_code, 2);
  EXPECT_EQ(far.err, "msislab: unknown command 'xyzzy' (see msislab --help)\n");
}

TEST(Cli, MissingDatasetDirectory) {
  const TempDir tmp;
  const std::string missing = tmp.file("no_such_dataset");
  const std::string out = tmp.file("out");
  const CliResult result = run_msislab(
      "run " + shell_quote(missing) + " --method deadreckoning --out " + shell_quote(out), tmp);
  EXPECT_EQ(result.exit_code, 2);
  expect_one_error_line(result);
  EXPECT_NE(result.err.find(missing), std::string::npos) << result.err;
  EXPECT_FALSE(fs::exists(fs::path(out) / "trajectory.tum"));
}

TEST(Cli, TruncatedLogNamesFileAndLine) {
  const TempDir tmp;
  const fs::path dataset = tmp.path() / "dataset";
  testing::SyntheticOptions options;
  options.duration_s = 20.0;
  testing::write_synthetic_dataset(dataset, options);
  const std::string dvl = (dataset / "synth_DVL.log").string();
  const std::size_t line = testing::truncate_last_line(dvl);
  const std::string out = tmp.file("out");
  const CliResult result = run_msislab(
      "run " + shell_quote(dataset.string()) + " --method deadreckoning --out " + shell_quote(out),
      tmp);
  EXPECT_EQ(result.exit_code, 2);
  expect_one_error_line(result);
  EXPECT_NE(result.err.find(dvl + ":" + std::to_string(line) + ":"), std::string::npos)
      << result.err << "expected " << dvl << ":" << line << ":";
  EXPECT_FALSE(fs::exists(fs::path(out) / "trajectory.tum"));
}

TEST(Cli, GoodDatasetRunsAndWritesResults) {
  const TempDir tmp;
  const fs::path dataset = tmp.path() / "dataset";
  testing::SyntheticOptions options;
  options.duration_s = 60.0;
  testing::write_synthetic_dataset(dataset, options);
  const fs::path out = tmp.path() / "out";
  const CliResult result =
      run_msislab("run " + shell_quote(dataset.string()) + " --method deadreckoning --out " +
                      shell_quote(out.string()),
                  tmp);
  EXPECT_EQ(result.exit_code, 0) << result.err;
  EXPECT_TRUE(result.err.empty()) << result.err;
  EXPECT_NE(result.out.find("trajectory.tum"), std::string::npos) << result.out;
  EXPECT_TRUE(fs::is_regular_file(out / "trajectory.tum"));
  EXPECT_TRUE(fs::is_regular_file(out / "metrics.json"));
}

}  // namespace
}  // namespace msislab
