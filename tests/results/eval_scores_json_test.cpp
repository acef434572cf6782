// metrics.json's "alignment" and "rpe" members (msislab eval): written after the run's members,
// read back, absent from a run's own record, "rpe": null with GPS truth, and strict on read.
#include "results/eval_scores_json.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "io/input_error.hpp"
#include "results/results.hpp"
#include "test_support.hpp"

namespace msislab::results {
namespace {

using testing::read_text;
using testing::TempDir;
using testing::write_text;

RunMetrics metrics_with_scores() {
  RunMetrics metrics;
  metrics.method = "outside";
  metrics.truth = "tum";
  EvalScores scores;
  scores.alignment.method = "se2";
  scores.alignment.window_s = 60.0;
  scores.alignment.positions = 601;
  scores.alignment.t_offset_s = 1e9;
  scores.alignment.T_truth_estimate = Pose2(30.0, -7.0, 12.0 * M_PI / 180.0);
  RelativePoseError rpe;
  rpe.delta_m = 10.0;
  rpe.pairs = 2;
  rpe.translation_m = {0.5, 0.75, 0.5, 1.0};
  rpe.rotation_deg = {45.0, 63.5, 45.0, 90.0};
  scores.rpe = rpe;
  metrics.eval_scores = scores;
  return metrics;
}

TEST(EvalScoresJson, WrittenLastAndReadBack) {
  const TempDir tmp;
  write_metrics_json(tmp.file("metrics.json"), metrics_with_scores(), "");
  const std::string text = read_text(tmp.file("metrics.json"));
  EXPECT_NE(text.find("\"diagnostics\": {},\n  \"alignment\": {\"method\": \"se2\", \"window_s\": "
                      "60, \"positions\": 601, \"t_offset_s\": 1e+09, \"rotation_deg\": 12, "
                      "\"x_m\": 30, \"y_m\": -7},\n  \"rpe\": {\"delta_m\": 10, \"pairs\": 2, "
                      "\"translation_m\": {\"mean\": 0.5, \"rmse\": 0.75, \"median\": 0.5, "
                      "\"max\": 1}, \"rotation_deg\": {\"mean\": 45, \"rmse\": 63.5, "
                      "\"median\": 45, \"max\": 90}}\n}\n"),
            std::string::npos)
      << text;
  const StoredMetrics stored = read_metrics_json(tmp.file("metrics.json"));
  ASSERT_TRUE(stored.metrics.eval_scores.has_value());
  const EvalScores& scores = *stored.metrics.eval_scores;
  EXPECT_EQ(scores.alignment.method, "se2");
  EXPECT_EQ(scores.alignment.window_s, 60.0);
  EXPECT_EQ(scores.alignment.positions, 601u);
  EXPECT_EQ(scores.alignment.t_offset_s, 1e9);
  EXPECT_NEAR(scores.alignment.T_truth_estimate.yaw(), 12.0 * M_PI / 180.0, 1e-15);
  EXPECT_EQ(scores.alignment.T_truth_estimate.x(), 30.0);
  ASSERT_TRUE(scores.rpe.has_value());
  EXPECT_EQ(scores.rpe->pairs, 2u);
  EXPECT_EQ(scores.rpe->translation_m.rmse, 0.75);
  EXPECT_EQ(scores.rpe->rotation_deg.max, 90.0);
}

TEST(EvalScoresJson, AbsentFromARunsRecordNullWithoutHeadingsOrPairs) {
  const TempDir tmp;
  RunMetrics metrics = metrics_with_scores();
  metrics.eval_scores.reset();
  write_metrics_json(tmp.file("run.json"), metrics, "");
  EXPECT_EQ(read_text(tmp.file("run.json")).find("alignment"), std::string::npos);
  EXPECT_FALSE(read_metrics_json(tmp.file("run.json")).metrics.eval_scores.has_value());

  metrics = metrics_with_scores();
  metrics.eval_scores->rpe.reset();  // GPS truth
  write_metrics_json(tmp.file("gps.json"), metrics, "");
  EXPECT_NE(read_text(tmp.file("gps.json")).find("\n  \"rpe\": null\n}"), std::string::npos);
  EXPECT_FALSE(read_metrics_json(tmp.file("gps.json")).metrics.eval_scores->rpe.has_value());

  metrics = metrics_with_scores();
  metrics.eval_scores->rpe->pairs = 0;  // a path shorter than delta
  write_metrics_json(tmp.file("short.json"), metrics, "");
  EXPECT_NE(read_text(tmp.file("short.json"))
                .find("\"pairs\": 0, \"translation_m\": null, \"rotation_deg\": null"),
            std::string::npos);
  EXPECT_EQ(read_metrics_json(tmp.file("short.json")).metrics.eval_scores->rpe->pairs, 0u);
}

TEST(EvalScoresJson, MalformedMembersNameTheirKey) {
  const TempDir tmp;
  write_metrics_json(tmp.file("metrics.json"), metrics_with_scores(), "");
  std::string text = read_text(tmp.file("metrics.json"));
  text.replace(text.find("\"positions\": 601"), 16, "\"positions\": -1");
  write_text(tmp.file("metrics.json"), text);
  try {
    read_metrics_json(tmp.file("metrics.json"));
    ADD_FAILURE() << "no InputError";
  } catch (const io::InputError& e) {
    EXPECT_NE(std::string(e.what()).find("key 'alignment.positions'"), std::string::npos)
        << e.what();
  }
}

}  // namespace
}  // namespace msislab::results
