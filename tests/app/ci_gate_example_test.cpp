// examples/ci_gate: the CI job docs/cli.md shows a user (a Monte Carlo of their external method
// beside msislab's dead reckoning, gated by msislab check) runs as written and passes; the same
// results against a stricter expectation fail the gate with a JUnit failure.
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

const std::string kExample = std::string(MSISLAB_SOURCE_DIR) + "/examples/ci_gate";

TEST(CiGateExample, TheJobPassesAndAStricterGateFails) {
  const TempDir tmp;
  const std::string out = tmp.file("job");
  const std::string log = tmp.file("job.log");
  const std::string job = "MSISLAB=" + shell_quote(MSISLAB_EXE) + " " +
                          shell_quote(kExample + "/ci_job.sh") + " " + shell_quote(out) + " >" +
                          shell_quote(log) + " 2>&1 </dev/null";
  const int status = std::system(job.c_str());
  ASSERT_TRUE(WIFEXITED(status));
  ASSERT_EQ(WEXITSTATUS(status), 0) << read_text(log);
  EXPECT_NE(read_text(log).find("4 of 4 expectations met, 0 missed"), std::string::npos)
      << read_text(log);
  EXPECT_NE(read_text(out + "/check.xml").find("tests=\"4\" failures=\"0\""), std::string::npos);

  const std::string strict = testing::write_text(
      tmp.file("strict.yaml"),
      "expectations:\n"
      "  - {name: mydr within 1 cm, result: basin, method: mydr, at_most: 0.01}\n");
  const testing::CliResult r = testing::run_msislab(
      "check " + shell_quote(strict) + " basin=" + shell_quote(out + "/montecarlo") + " --junit " +
          shell_quote(tmp.file("strict.xml")),
      tmp);
  EXPECT_EQ(r.exit_code, 1) << r.out << r.err;
  EXPECT_NE(r.err.find("MISS mydr within 1 cm: mydr mean_error_m = "), std::string::npos) << r.err;
  EXPECT_NE(read_text(tmp.file("strict.xml")).find("<failure message=\"mydr mean_error_m = "),
            std::string::npos);
}

}  // namespace
}  // namespace msislab
