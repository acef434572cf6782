// examples/ci_gate: the CI job docs/cli.md shows a user (a Monte Carlo of their external method
// beside msislab's dead reckoning, gated by msislab check) runs as written, from a checkout's root
// with a relative OUT (`examples/ci_gate/ci_job.sh out`), and passes; the same results against a
// stricter expectation, given as relative paths too, fail the gate with a JUnit failure.
#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <string>

#include "cli_runner.hpp"
#include "test_support.hpp"

namespace msislab {
namespace {

namespace fs = std::filesystem;
using testing::read_text;
using testing::shell_quote;
using testing::TempDir;

TEST(CiGateExample, TheJobPassesAndAStricterGateFails) {
  const TempDir tmp;
  // A checkout's root as the job sees it, the job started from it: the example's folders and the
  // scenarios and scenes it reads, copied (300 kB).
  const fs::path source(MSISLAB_SOURCE_DIR);
  for (const char* folder :
       {"examples/ci_gate", "examples/external_method", "scenarios", "scenes"}) {
    fs::create_directories(tmp.path() / folder);
    fs::copy(source / folder, tmp.path() / folder, fs::copy_options::recursive);
  }
  const std::string cd = "cd " + shell_quote(tmp.path().string()) + " && ";
  const std::string log = tmp.file("job.log");
  const std::string job = cd + "MSISLAB=" + shell_quote(MSISLAB_EXE) +
                          " examples/ci_gate/ci_job.sh out >" + shell_quote(log) +
                          " 2>&1 </dev/null";
  const int status = std::system(job.c_str());
  ASSERT_TRUE(WIFEXITED(status));
  ASSERT_EQ(WEXITSTATUS(status), 0) << read_text(log);
  EXPECT_NE(read_text(log).find("3 of 3 expectations met, 0 missed"), std::string::npos)
      << read_text(log);
  EXPECT_NE(read_text(tmp.file("out/check.xml")).find("tests=\"3\" failures=\"0\""),
            std::string::npos);

  testing::write_text(tmp.file("strict.yaml"),
                      "expectations:\n"
                      "  - {name: mydr within 1 cm, result: basin, method: mydr, at_most: 0.01}\n");
  const testing::CliResult r =
      testing::run_shell(cd + shell_quote(MSISLAB_EXE) +
                             " check strict.yaml basin=out/montecarlo --junit out/strict.xml",
                         tmp);
  EXPECT_EQ(r.exit_code, 1) << r.out << r.err;
  EXPECT_NE(r.err.find("MISS mydr within 1 cm: mydr mean_error_m = "), std::string::npos) << r.err;
  EXPECT_NE(read_text(tmp.file("out/strict.xml")).find("<failure message=\"mydr mean_error_m = "),
            std::string::npos);
}

}  // namespace
}  // namespace msislab
