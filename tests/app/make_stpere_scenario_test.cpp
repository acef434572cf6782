// msislab_make_stpere_scenario replaces only its own outputs: a scenario it wrote (its opening
// comment says so) and the heading history that scenario names; any other file at --out or
// --heading-out, or one path for both, is refused with exit status 2 before anything is written.
// Needs the real St. Pere dataset (skips without it).
#include <gtest/gtest.h>

#include <string>

#include "cli_runner.hpp"
#include "test_support.hpp"

namespace msislab {
namespace {

using testing::read_text;
using testing::run_shell;
using testing::shell_quote;
using testing::TempDir;
using testing::write_text;

/// Runs msislab_make_stpere_scenario (its path is MSISLAB_MAKE_STPERE_SCENARIO, set by CMake).
testing::CliResult run_tool(const std::string& args, const TempDir& tmp) {
  return run_shell(shell_quote(MSISLAB_MAKE_STPERE_SCENARIO) + " " + args, tmp);
}

std::string tool_args(const std::string& out, const std::string& heading) {
  return "--dataset " + shell_quote(testing::stpere_dir()) + " --scene " +
         shell_quote(std::string(MSISLAB_SOURCE_DIR) + "/scenes/stpere_marina.obj") + " --out " +
         shell_quote(out) + " --heading-out " + shell_quote(heading);
}

TEST(MakeStPereScenario, ReplacesOnlyWhatItWrote) {
  MSISLAB_REQUIRE_STPERE();
  const TempDir tmp;
  const std::string scenario = tmp.file("replica.yaml"), heading = tmp.file("heading.csv");
  // Written, then written again over its own files.
  for (int pass = 0; pass < 2; ++pass) {
    const auto r = run_tool(tool_args(scenario, heading), tmp);
    ASSERT_EQ(r.exit_code, 0) << pass << ": " << r.err;
  }
  EXPECT_NE(read_text(scenario).find("heading_csv: heading.csv"), std::string::npos);
  EXPECT_EQ(read_text(heading).rfind("t_s,yaw_deg\n", 0), 0u);

  // A user's files at either path are left as they are.
  const std::string mine = write_text(tmp.file("mine.yaml"), "my notes\n");
  const std::string my_csv = write_text(tmp.file("mine.csv"), "t_s,yaw_deg\n0,1\n1,2\n");
  auto r = run_tool(tool_args(mine, tmp.file("other.csv")), tmp);
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find(mine + ": is a file that msislab did not write"), std::string::npos)
      << r.err;
  EXPECT_EQ(read_text(mine), "my notes\n");
  EXPECT_FALSE(std::filesystem::exists(tmp.file("other.csv")));
  r = run_tool(tool_args(tmp.file("new.yaml"), my_csv), tmp);
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find(my_csv + ": is a file that msislab did not write"), std::string::npos)
      << r.err;
  EXPECT_EQ(read_text(my_csv), "t_s,yaw_deg\n0,1\n1,2\n");
  // The tool's own heading history, but named by a new scenario: not known for its own there.
  r = run_tool(tool_args(tmp.file("new.yaml"), heading), tmp);
  EXPECT_EQ(r.exit_code, 2);
  // One path for both.
  r = run_tool(tool_args(tmp.file("new.yaml"), tmp.file("new.yaml")), tmp);
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("is also --out"), std::string::npos) << r.err;
  EXPECT_FALSE(std::filesystem::exists(tmp.file("new.yaml")));
}

}  // namespace
}  // namespace msislab
