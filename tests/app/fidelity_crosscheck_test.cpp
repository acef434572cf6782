// The sonar rows of `msislab fidelity` against tools/fidelity_crosscheck.py, a second
// implementation in Python written from the definitions of docs/fidelity.md: on two small
// synthetic datasets, on the real St. Pere data against itself, and on the real data against the
// simulated replica (scenarios/stpere_replica.yaml). Every row the script computes must equal
// fidelity.json's to 1e-9 relative: both count the same samples and take quantiles at
// (n - 1) p, so only the order of floating-point operations differs (100 x (count / n) against
// 100 count / n, the interpolation's arithmetic), a few ulps. CMake adds this test only when it
// finds python3; --out draws, so it runs under `xvfb-run -a`.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <future>
#include <set>
#include <string>
#include <utility>
#include <vector>

#include "cli_runner.hpp"
#include "io/json.hpp"
#include "synthetic_detections.hpp"
#include "test_support.hpp"

namespace msislab {
namespace {

namespace fs = std::filesystem;
using testing::CliResult;
using testing::shell_quote;
using testing::TempDir;

constexpr double kRelativeTolerance = 1e-9;

/// Runs the script on the datasets (stdout and stderr captured in tmp).
CliResult run_script(const std::vector<std::string>& datasets, const TempDir& tmp) {
  std::string command =
      shell_quote(testing::python3()) + " " +
      shell_quote(std::string(MSISLAB_SOURCE_DIR) + "/tools/fidelity_crosscheck.py");
  for (const std::string& d : datasets) command += " " + shell_quote(d);
  return testing::run_shell(command, tmp);
}

io::Json script_rows(const CliResult& result) {
  EXPECT_EQ(result.exit_code, 0) << result.err;
  EXPECT_EQ(result.err, "");
  return io::parse_json(result.out, "fidelity_crosscheck.py output");
}

/// fidelity.json of `msislab fidelity REAL SIM --out`.
io::Json fidelity_json(const std::string& real, const std::string& sim, const TempDir& tmp,
                       const std::string& name) {
  const fs::path out = tmp.path() / name;
  const CliResult result =
      testing::run_msislab("fidelity " + shell_quote(real) + " " + shell_quote(sim) + " --out " +
                               shell_quote(out.string()),
                           tmp);
  EXPECT_EQ(result.exit_code, 0) << result.err;
  return io::read_json_file((out / "fidelity.json").string());
}

void expect_same(const io::Json& script, const io::Json& msislab, const std::string& what) {
  SCOPED_TRACE(what);
  ASSERT_EQ(script.is_null(), msislab.is_null()) << "script " << script << ", msislab " << msislab;
  if (script.is_null()) return;
  const double a = script.get<double>(), b = msislab.get<double>();
  EXPECT_LE(std::abs(a - b), kRelativeTolerance * std::max(std::abs(a), std::abs(b)))
      << "script " << a << ", msislab " << b;
}

/// The rows the script computes: every row of these sections except the echo extent's.
const std::set<std::string> kCheckedSections = {"Per beam", "Detected range by 10 m band",
                                                "Sonar rotation"};

/// Every row of the checked sections of fidelity.json against the script's row of that key:
/// each pair (script side, fidelity.json side) of `sides`, and the KS distance when `ks`.
void expect_rows_match(const io::Json& script, const io::Json& fidelity,
                       const std::vector<std::pair<std::string, std::string>>& sides, bool ks) {
  std::size_t checked = 0;
  for (const io::Json& row : fidelity.at("rows")) {
    const std::string key = row.at("key").get<std::string>();
    if (!kCheckedSections.count(row.at("section").get<std::string>())) continue;
    SCOPED_TRACE(key);
    ASSERT_TRUE(script.contains(key)) << "the script has no row " << key;
    for (const auto& [script_side, fidelity_side] : sides) {
      expect_same(script.at(key).at(script_side), row.at(fidelity_side),
                  script_side + " against " + fidelity_side);
    }
    if (ks) expect_same(script.at(key).value("ks", io::Json()), row.at("ks"), "ks");
    ++checked;
  }
  // 8 per beam, 3 quantiles and 2 x 5 bands of range, 2 of rotation: none left out on either side.
  EXPECT_EQ(checked, 23u);
  EXPECT_EQ(script.size(), checked);
}

TEST(FidelityCrosscheck, SyntheticPair) {
  MSISLAB_REQUIRE_PYTHON3();
  const TempDir tmp;
  const fs::path real = tmp.path() / "real", sim = tmp.path() / "sim";
  testing::write_detection_dataset(real);
  testing::DetectionPattern pattern;
  pattern.prefix = "replica";
  pattern.period = 4;
  pattern.detected_per_period = 3;
  pattern.first_m = 11.0;
  testing::write_detection_dataset(sim, pattern);
  const io::Json script = script_rows(run_script({real.string(), sim.string()}, tmp));
  expect_rows_match(script, fidelity_json(real.string(), sim.string(), tmp, "report"),
                    {{"real", "real"}, {"sim", "sim"}}, true);
}

// The real data against itself (both columns are the real data's) and against the replica: the
// per-beam figures of docs/fidelity.md come from here.
TEST(FidelityCrosscheck, StPereAgainstItselfAndTheReplica) {
  MSISLAB_REQUIRE_PYTHON3();
  MSISLAB_REQUIRE_STPERE();
  const TempDir tmp;
  const std::string real = testing::stpere_dir(), replica = tmp.file("replica");
  const CliResult simulated = testing::run_msislab(
      "simulate " +
          shell_quote(std::string(MSISLAB_SOURCE_DIR) + "/scenarios/stpere_replica.yaml") +
          " --out " + shell_quote(replica),
      tmp);
  ASSERT_EQ(simulated.exit_code, 0) << simulated.err;
  // The script beside msislab: each takes one core for most of the test's time.
  std::future<CliResult> script_run = std::async(std::launch::async, [&] {
    return run_script({real, replica}, tmp);
  });
  const io::Json self = fidelity_json(real, real, tmp, "self");
  const io::Json against_replica = fidelity_json(real, replica, tmp, "replica_report");
  const io::Json script = script_rows(script_run.get());
  {
    SCOPED_TRACE("real against itself");
    expect_rows_match(script, self, {{"real", "real"}, {"real", "sim"}}, false);
  }
  {
    SCOPED_TRACE("real against the replica");
    expect_rows_match(script, against_replica, {{"real", "real"}, {"sim", "sim"}}, true);
  }
}

// Bad input: one line naming the file and line, exit status 2.
TEST(FidelityCrosscheck, MalformedRowIsOneLine) {
  MSISLAB_REQUIRE_PYTHON3();
  const TempDir tmp;
  const fs::path dir = tmp.path() / "bad";
  fs::remove(testing::write_detection_dataset(dir));
  const std::string csv = (dir / "synth_detections.csv").string();
  testing::write_text(csv,
                      "keyframe,beam_row,t_log_s,sensor_time_ms,angle_idx,angle_rad,range_m\n"
                      "1,5,1000000000.345,345,199,6.25,10\n"
                      "1,6,1000000000.414,414,198,6.22,abc\n");
  const CliResult result = run_script({dir.string()}, tmp);
  EXPECT_EQ(result.exit_code, 2);
  EXPECT_EQ(result.out, "");
  EXPECT_EQ(std::count(result.err.begin(), result.err.end(), '\n'), 1) << result.err;
  EXPECT_NE(result.err.find(csv + ":3: 'abc' is not a number"), std::string::npos) << result.err;
}

}  // namespace
}  // namespace msislab
