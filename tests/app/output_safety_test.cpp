// Never destroy what msislab did not write, end to end through the executable: every command that
// writes refuses a plain file, a folder of other things, an input of its own or a folder holding
// one, and the current directory, with exit status 2 and one line naming the path, and leaves the
// user's files byte for byte as they were; a second run into an earlier output of the same
// command replaces it (docs/cli.md, "Outputs").
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <map>
#include <string>

#include "cli_runner.hpp"
#include "io/output_guard.hpp"
#include "test_support.hpp"

namespace msislab::app {
namespace {

namespace fs = std::filesystem;
using testing::CliResult;
using testing::read_text;
using testing::run_msislab;
using testing::shell_quote;
using testing::TempDir;
using testing::write_text;

const std::string kScenario = std::string(MSISLAB_SOURCE_DIR) + "/scenarios/small_basin.yaml";

/// Every file below `dir` with its bytes.
std::map<std::string, std::string> snapshot(const fs::path& dir) {
  std::map<std::string, std::string> files;
  for (const auto& entry : fs::recursive_directory_iterator(dir)) {
    const std::string name = fs::relative(entry.path(), dir).string();
    files[name] = entry.is_regular_file() ? read_text(entry.path().string()) : "<folder>";
  }
  return files;
}

/// A working folder with the user's things: a file, a folder of notes, a simulated dataset `sim`
/// and a result `res` of it, each made by msislab.
class OutputSafety : public ::testing::Test {
 protected:
  void SetUp() override {
    write_text(tmp.file("f"), "the user's file\n");
    fs::create_directory(tmp.path() / "mydir");
    write_text(tmp.file("mydir/keep.txt"), "keep me\n");
    write_text(tmp.file("mine.md"), "# my notes\n");
    write_text(tmp.file("mine.png"), "not msislab's image\n");
    ASSERT_EQ(msislab("simulate " + shell_quote(kScenario) + " -o sim").exit_code, 0);
    ASSERT_EQ(msislab("run sim -m deadreckoning -o res").exit_code, 0);
  }

  /// Runs msislab in the working folder.
  CliResult msislab(const std::string& args) {
    return run_msislab(args, tmp, "cd " + shell_quote(tmp.path().string()) + " &&");
  }

  /// Runs a command that must be refused: exit 2, one line on stderr naming `path`, nothing in
  /// the working folder changed and nothing left behind.
  void expect_refused(const std::string& args, const std::string& path) {
    const auto before = snapshot(tmp.path());
    const CliResult r = msislab(args);
    EXPECT_EQ(r.exit_code, 2) << args << "\n" << r.out << r.err;
    EXPECT_EQ(r.err.rfind("msislab: " + path + ": ", 0), 0u) << args << ": " << r.err;
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
    auto after = snapshot(tmp.path());
    after.erase("stdout.txt");
    after.erase("stderr.txt");
    auto expected = before;
    expected.erase("stdout.txt");
    expected.erase("stderr.txt");
    EXPECT_EQ(after, expected) << args << " changed or left files behind";
  }

  TempDir tmp;
};

TEST_F(OutputSafety, SimulateRefusesAFileAFolderOfOtherThingsAndTheCurrentDirectory) {
  const std::string simulate = "simulate " + shell_quote(kScenario) + " -o ";
  expect_refused(simulate + "f", "f");
  expect_refused(simulate + "mydir", "mydir");
  expect_refused(simulate + ".", ".");
  expect_refused(simulate + "res", "res");  // msislab's, but a result, not a dataset
}

TEST_F(OutputSafety, SimulateReplacesItsOwnEarlierDatasetButNotAFileTheUserAdded) {
  const std::string before = read_text(tmp.file("sim/small_basin_IS.log"));
  const CliResult r = msislab("simulate " + shell_quote(kScenario) + " -o sim --seed 2");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(read_text(tmp.file("sim/small_basin_IS.log")), before) << "not replaced";
  EXPECT_EQ(io::output_kind(tmp.file("sim")), "dataset");
  for (const auto& entry : fs::directory_iterator(tmp.path())) {
    EXPECT_NE(entry.path().filename().string()[0], '.') << "left behind: " << entry.path();
  }
  write_text(tmp.file("sim/my_notes.txt"), "the user's\n");
  expect_refused("simulate " + shell_quote(kScenario) + " -o sim", "sim");
}

TEST_F(OutputSafety, ForceReplacesAForeignFolderTheUserNames) {
  const CliResult r = msislab("simulate " + shell_quote(kScenario) + " -o mydir --force");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_FALSE(fs::exists(tmp.path() / "mydir" / "keep.txt"));
  expect_refused("simulate " + shell_quote(kScenario) + " -o .. --force", "..");
}

TEST_F(OutputSafety, RunRefusesItsInputAndForeignPaths) {
  expect_refused("run sim -m deadreckoning -o sim", "sim");
  expect_refused("run sim -m deadreckoning -o mydir", "mydir");
  expect_refused("run sim -m deadreckoning -o f", "f");
  expect_refused("run sim -m deadreckoning -o ..", "..");
  const CliResult again = msislab("run sim -m deadreckoning -o res");
  EXPECT_EQ(again.exit_code, 0) << again.err;
}

TEST_F(OutputSafety, ReportRefusesAFolderPageAndAnInputAsItsFiguresFolder) {
  fs::create_directory(tmp.path() / "out");
  fs::rename(tmp.path() / "res", tmp.path() / "out" / "deadreckoning");
  fs::create_directory(tmp.path() / "victim");
  write_text(tmp.file("victim/thesis.tex"), "months of work\n");
  expect_refused("report victim --sim out", "victim");
  expect_refused("report victim.md --sim out", "victim");
  expect_refused("report out.md --sim out", "out");  // the figures folder would be the input
  expect_refused("report mine.md --sim out", "mine.md");
  expect_refused("report mydir.md --sim out", "mydir");
}

TEST_F(OutputSafety, ScansImageSegmentAndFidelityRefuseTheUsersFiles) {
  expect_refused("scans sim -o mydir", "mydir");
  expect_refused("scans sim -o sim", "sim");
  expect_refused("image sim -o mine.png", "mine.png");
  expect_refused("image sim -o mydir", "mydir");
  expect_refused("segment sim -o mine.md", "mine.md");
  expect_refused("fidelity sim sim --out mydir", "mydir");
  const CliResult image = msislab("image sim -o image.png");
  ASSERT_EQ(image.exit_code, 0) << image.err;
  EXPECT_TRUE(io::png_written_by_msislab(tmp.file("image.png")));
  EXPECT_EQ(msislab("image sim -o image.png").exit_code, 0) << "its own image is replaced";
  ASSERT_EQ(msislab("segment sim -o table.md").exit_code, 0);
  EXPECT_EQ(msislab("segment sim -o table.md").exit_code, 0) << "its own page is replaced";
}

TEST_F(OutputSafety, MonteCarloRefusesAForeignFolderAndADataset) {
  expect_refused(
      "montecarlo " + shell_quote(kScenario) + " --runs 1 --methods deadreckoning -o mydir",
      "mydir");
  expect_refused(
      "montecarlo " + shell_quote(kScenario) + " --runs 1 --methods deadreckoning -o sim", "sim");
}

TEST_F(OutputSafety, EvalAddsScoresToAnOutsideFolderButNeverReplacesTheUsersOwn) {
  fs::create_directory(tmp.path() / "theirs");
  fs::copy_file(tmp.path() / "res" / "trajectory.tum", tmp.path() / "theirs" / "trajectory.tum");
  const std::string eval = "eval theirs --truth sim/truth/trajectory.tum --name mine";
  const CliResult first = msislab(eval);
  ASSERT_EQ(first.exit_code, 0) << first.err;
  EXPECT_EQ(io::output_kind(tmp.file("theirs")), "scores");
  EXPECT_EQ(msislab(eval).exit_code, 0) << "its own scores are replaced";
  fs::create_directory(tmp.path() / "other");
  fs::copy_file(tmp.path() / "res" / "trajectory.tum", tmp.path() / "other" / "trajectory.tum");
  write_text(tmp.file("other/metrics.json"), "{\"theirs\": true}\n");
  expect_refused("eval other --truth sim/truth/trajectory.tum", "other/metrics.json");
}

}  // namespace
}  // namespace msislab::app
