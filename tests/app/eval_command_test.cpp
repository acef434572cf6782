// `msislab eval`: re-scoring a result directory reproduces what `msislab run` wrote, byte for byte,
// and adds its alignment and RPE; nees.csv against a hand computation; --truth, --config and a
// result without truth; bad input.
#include "app/eval_command.hpp"

#include <gtest/gtest.h>

#include <Eigen/LU>
#include <cmath>
#include <filesystem>
#include <string>

#include "app/run_command.hpp"
#include "app/simulate_command.hpp"
#include "io/input_error.hpp"
#include "io/tum.hpp"
#include "results/results.hpp"
#include "test_support.hpp"

namespace msislab::app {
namespace {

namespace fs = std::filesystem;
using testing::read_text;
using testing::TempDir;
using testing::write_text;

constexpr const char* kSegments =
    "segments:\n"
    "  first_leg: [0, 30]\n"
    "  rest: [30, 200]\n";

// small_basin simulated once; each test runs its methods into its own folder.
struct SmallBasin {
  TempDir tmp;
  fs::path dataset = tmp.path() / "dataset";
  std::string config = write_text(tmp.file("slam.yaml"), kSegments);
  SmallBasin() {
    simulate({std::string(MSISLAB_SOURCE_DIR) + "/scenarios/small_basin.yaml", dataset.string(),
              std::nullopt, 2});
  }
};
const SmallBasin& small_basin() {
  static const SmallBasin basin;
  return basin;
}

// metrics.json without the members only `msislab eval` writes (the last two: "alignment", "rpe").
std::string without_eval_members(std::string json) {
  const std::size_t at = json.find(",\n  \"alignment\": ");
  EXPECT_NE(at, std::string::npos) << json;
  EXPECT_NE(json.find("\n  \"rpe\": ", at), std::string::npos) << json;
  if (at != std::string::npos) json.replace(at, json.rfind("\n}") - at, "");
  return json;
}

EvalOptions options_for(const std::string& result_dir, const std::string& truth_path,
                        const std::string& config_path) {
  EvalOptions options;
  options.result_dir = result_dir;
  options.truth_path = truth_path;
  options.config_path = config_path;
  return options;
}

fs::path run_method(const std::string& method, const fs::path& out) {
  run({small_basin().dataset.string(), method, out.string(), small_basin().config});
  return out;
}

TEST(EvalCommand, ReproducesWhatRunWrote) {
  const TempDir tmp;
  for (const std::string method : {"worldcentric", "deadreckoning"}) {
    const fs::path out = run_method(method, tmp.path() / method);
    const std::string metrics = read_text((out / "metrics.json").string());
    EXPECT_NE(metrics.find("\"segment_windows\": {\"first_leg\": [0, 30], \"rest\": [30, 200]}"),
              std::string::npos)
        << metrics;
    // Dead reckoning scores the scans it places like the SLAM scores its own.
    ASSERT_TRUE(fs::exists(out / "nees.csv")) << method;
    EXPECT_TRUE(fs::exists(out / "scans.csv") && fs::exists(out / "map.ply")) << method;
    const std::string nees = read_text((out / "nees.csv").string());

    const EvalOutcome outcome = evaluate(options_for(out.string(), "", ""));
    const std::string rescored = read_text((out / "metrics.json").string());
    EXPECT_EQ(without_eval_members(rescored), metrics) << method;
    // No alignment by default, and the RPE over 10 m against the simulation's poses.
    EXPECT_NE(rescored.find("\"alignment\": {\"method\": \"none\", \"window_s\": null, "
                            "\"positions\": 0, \"t_offset_s\": 0, \"rotation_deg\": 0, "
                            "\"x_m\": 0, \"y_m\": 0}"),
              std::string::npos)
        << rescored;
    EXPECT_NE(rescored.find("\"rpe\": {\"delta_m\": 10, \"pairs\": "), std::string::npos)
        << rescored;
    EXPECT_TRUE(outcome.metrics.anees.has_value());
    EXPECT_EQ(read_text((out / "nees.csv").string()), nees);
    EXPECT_GT(outcome.nees_rows, 3u);
  }
}

// Parses the "scan,t_s,nees" rows of nees.csv.
std::vector<results::NeesSample> nees_rows(const fs::path& dir) {
  return results::read_nees_csv((dir / "nees.csv").string());
}

TEST(EvalCommand, NeesCsvMatchesAHandComputation) {
  const TempDir tmp;
  const fs::path out = run_method("worldcentric", tmp.path() / "wc");
  const std::vector<StampedPose> scans = results::read_scans_csv((out / "scans.csv").string());
  const std::vector<io::TumPose> truth =
      io::read_tum((small_basin().dataset / "truth" / "trajectory.tum").string());
  const std::vector<results::NeesSample> nees = nees_rows(out);
  ASSERT_EQ(nees.size(), scans.size());
  double sum = 0.0;
  for (std::size_t k = 0; k < scans.size(); ++k) {
    // Truth linearly interpolated between the stamps around the scan time (10 Hz).
    std::size_t j = 1;
    while (j + 1 < truth.size() && truth[j].t_s < scans[k].t_s) ++j;
    const io::TumPose& a = truth[j - 1];
    const io::TumPose& b = truth[j];
    const double w = (scans[k].t_s - a.t_s) / (b.t_s - a.t_s);
    const double dyaw = std::remainder(b.yaw_rad - a.yaw_rad, 2.0 * M_PI);
    const Eigen::Vector3d t(a.x_m + w * (b.x_m - a.x_m), a.y_m + w * (b.y_m - a.y_m),
                            a.yaw_rad + w * dyaw);
    const Pose2& est = scans[k].pose.mean;
    const Eigen::Vector3d e(est.x() - t.x(), est.y() - t.y(),
                            std::remainder(est.yaw() - t.z(), 2.0 * M_PI));
    const double expected = e.dot(scans[k].pose.cov.inverse() * e);
    EXPECT_NEAR(nees[k].nees, expected, 1e-9 * std::max(1.0, expected)) << "scan " << k;
    EXPECT_EQ(nees[k].t_s, scans[k].t_s);
    sum += expected;
  }
  const results::StoredMetrics stored = results::read_metrics_json((out / "metrics.json").string());
  ASSERT_TRUE(stored.metrics.anees);
  EXPECT_NEAR(*stored.metrics.anees, sum / static_cast<double>(scans.size()), 1e-9);
}

TEST(EvalCommand, TruthFileAndConfigOverride) {
  const TempDir tmp;
  const fs::path out = run_method("worldcentric", tmp.path() / "wc");
  const results::StoredMetrics before = results::read_metrics_json((out / "metrics.json").string());
  // The truth shifted 3 m north: every position error grows, and the NEES with it.
  std::vector<io::TumPose> shifted =
      io::read_tum((small_basin().dataset / "truth" / "trajectory.tum").string());
  for (io::TumPose& p : shifted) p.y_m += 3.0;
  const std::string truth_file = tmp.file("shifted.tum");
  io::write_tum(truth_file, shifted);
  const std::string config = write_text(tmp.file("whole.yaml"), "segments:\n  all: [0, 1000]\n");

  const EvalOutcome outcome = evaluate(options_for(out.string(), truth_file, config));
  const results::StoredMetrics after = results::read_metrics_json((out / "metrics.json").string());
  EXPECT_EQ(after.metrics.truth, "tum");
  EXPECT_GT(after.metrics.errors.mean_m, before.metrics.errors.mean_m + 1.0);
  EXPECT_GT(*after.metrics.anees, 3.0 * *before.metrics.anees);
  ASSERT_EQ(after.metrics.segments.size(), 1u);
  EXPECT_EQ(after.metrics.segments[0].first, "all");
  EXPECT_DOUBLE_EQ(*after.metrics.segments[0].second, after.metrics.errors.mean_m);
  // The run's own figures are kept, and so is the dataset.
  EXPECT_EQ(after.metrics.method, "worldcentric");
  EXPECT_EQ(after.metrics.scans, before.metrics.scans);
  EXPECT_EQ(after.metrics.matches_accepted, before.metrics.matches_accepted);
  EXPECT_EQ(after.metrics.runtime_s, before.metrics.runtime_s);
  EXPECT_EQ(after.metrics.diagnostics, before.metrics.diagnostics);
  EXPECT_EQ(after.dataset_dir, before.dataset_dir);
  EXPECT_NE(read_text((out / "metrics.json").string()).find("\"truth_file\": \"" + truth_file),
            std::string::npos);
  EXPECT_EQ(outcome.metrics.errors.mean_m, after.metrics.errors.mean_m);
}

TEST(EvalCommand, ResultWithoutMetricsNeedsATruthFile) {
  const TempDir tmp;
  const fs::path out = run_method("worldcentric", tmp.path() / "wc");
  fs::remove(out / "metrics.json");
  fs::remove(out / "nees.csv");
  EXPECT_THROW(evaluate(options_for(out.string(), "", "")), io::InputError);
  const std::string truth = (small_basin().dataset / "truth" / "trajectory.tum").string();
  const EvalOutcome outcome = evaluate(options_for(out.string(), truth, ""));
  EXPECT_EQ(outcome.metrics.method, "unknown");
  EXPECT_EQ(outcome.metrics.scans, static_cast<int>(outcome.nees_rows));
  EXPECT_TRUE(fs::exists(out / "metrics.json"));
  EXPECT_TRUE(fs::exists(out / "nees.csv"));
}

// Expects evaluate() to throw InputError whose message contains `word`.
void expect_rejected(const EvalOptions& options, const std::string& word) {
  try {
    evaluate(options);
    ADD_FAILURE() << "no InputError";
  } catch (const io::InputError& e) {
    EXPECT_NE(std::string(e.what()).find(word), std::string::npos) << e.what();
  }
}

TEST(EvalCommand, BadInput) {
  const TempDir tmp;
  expect_rejected(options_for(tmp.file("missing"), "", ""), tmp.file("missing"));
  // The dataset recorded in metrics.json is gone.
  const fs::path out = tmp.path() / "dr";
  run({small_basin().dataset.string(), "deadreckoning", out.string(), ""});
  std::string json = read_text((out / "metrics.json").string());
  const std::string dataset = fs::absolute(small_basin().dataset).lexically_normal().string();
  json.replace(json.find(dataset), dataset.size(), tmp.file("gone"));
  write_text((out / "metrics.json").string(), json);
  expect_rejected(options_for(out.string(), "", ""), "--truth");
  // A malformed metrics.json names its key.
  write_text((out / "metrics.json").string(), "{\"method\": 3}");
  expect_rejected(options_for(out.string(), "", ""), "key 'method'");
  write_text((out / "metrics.json").string(), "{\"method\": \"x\",");
  expect_rejected(options_for(out.string(), "", ""), "metrics.json:1:");
}

}  // namespace
}  // namespace msislab::app
