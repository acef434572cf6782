// `msislab run` as a function: a noise-free synthetic dataset scored against its simulation truth,
// the result files and their keys (docs/interfaces.md), named segments, stale results, the real
// St. Pere logs against GPS, and bad input rejected before anything is written.
#include "app/run_command.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <optional>
#include <string>

#include "io/input_error.hpp"
#include "io/tum.hpp"
#include "synthetic_dataset.hpp"
#include "test_support.hpp"

namespace msislab::app {
namespace {

namespace fs = std::filesystem;
using testing::read_text;
using testing::TempDir;
using testing::write_text;

// The number after "key": in a flat JSON text; nullopt when the key is absent or not a number.
std::optional<double> json_value(const std::string& json, const std::string& key) {
  const std::string quoted = "\"" + key + "\":";
  const std::size_t at = json.find(quoted);
  if (at == std::string::npos) return std::nullopt;
  const char* begin = json.c_str() + at + quoted.size();
  char* end = nullptr;
  const double value = std::strtod(begin, &end);
  if (end == begin) return std::nullopt;
  return value;
}

// The text of the "segments" object, without its braces.
std::string json_segments(const std::string& json) {
  const std::string key = "\"segments\": {";
  const std::size_t begin = json.find(key);
  if (begin == std::string::npos) return "";
  const std::size_t end = json.find('}', begin);
  return json.substr(begin + key.size(), end - begin - key.size());
}

RunOptions options_for(const fs::path& dataset, const std::string& method, const fs::path& out,
                       const std::string& config = "") {
  RunOptions options;
  options.dataset_dir = dataset.string();
  options.method = method;
  options.out_dir = out.string();
  options.config_path = config;
  return options;
}

TEST(RunCommand, SyntheticDeadReckoningFollowsTheTruth) {
  const TempDir tmp;
  const fs::path dataset = tmp.path() / "dataset";
  const fs::path out = tmp.path() / "result";
  const std::vector<io::TumPose> truth = testing::write_synthetic_dataset(dataset);

  const RunOutcome outcome = run(options_for(dataset, "deadreckoning", out));
  ASSERT_TRUE(outcome.metrics.has_value());
  const RunMetrics& metrics = *outcome.metrics;
  std::printf("synthetic deadreckoning: mean %.4f m, max %.4f m, final %.4f m\n",
              metrics.errors.mean_m, metrics.errors.max_m, metrics.errors.final_m);
  EXPECT_EQ(metrics.method, "deadreckoning");
  EXPECT_EQ(metrics.truth, "simulation");
  EXPECT_EQ(metrics.errors.count, truth.size());
  EXPECT_LT(metrics.errors.mean_m, 0.5);
  EXPECT_LT(metrics.errors.max_m, 1.0);

  // metrics.json holds every key docs/interfaces.md requires, and the same figures.
  ASSERT_TRUE(fs::is_regular_file(out / "metrics.json"));
  const std::string json = read_text((out / "metrics.json").string());
  EXPECT_NE(json.find("\"method\": \"deadreckoning\""), std::string::npos) << json;
  EXPECT_NE(json.find("\"truth\": \"simulation\""), std::string::npos) << json;
  for (const char* key : {"mean_error_m", "rmse_m", "median_error_m", "max_error_m",
                          "final_error_m", "scans", "matches_accepted", "runtime_s"}) {
    EXPECT_TRUE(json_value(json, key).has_value()) << key << " missing or not a number:\n" << json;
  }
  EXPECT_NE(json.find("\"segments\": {"), std::string::npos) << json;
  EXPECT_EQ(json_value(json, "mean_error_m"), metrics.errors.mean_m);
  EXPECT_EQ(json_value(json, "max_error_m"), metrics.errors.max_m);

  // trajectory.tum: starts on the first truth pose, at least one pose per second over the run.
  ASSERT_TRUE(fs::is_regular_file(out / "trajectory.tum"));
  const std::vector<io::TumPose> estimate = io::read_tum((out / "trajectory.tum").string());
  ASSERT_GE(estimate.size(), 2u);
  EXPECT_EQ(estimate.front().t_s, truth.front().t_s);
  EXPECT_NEAR(estimate.front().x_m, truth.front().x_m, 1e-9);
  EXPECT_NEAR(estimate.front().y_m, truth.front().y_m, 1e-9);
  EXPECT_NEAR(estimate.front().z_m, truth.front().z_m, 1e-9);
  EXPECT_NEAR(estimate.front().yaw_rad, truth.front().yaw_rad, 1e-9);
  EXPECT_GE(estimate.back().t_s, truth.back().t_s - 1.0);
  double largest_gap_s = 0.0;
  for (std::size_t i = 1; i < estimate.size(); ++i) {
    largest_gap_s = std::max(largest_gap_s, estimate[i].t_s - estimate[i - 1].t_s);
  }
  EXPECT_LE(largest_gap_s, 1.0);
  EXPECT_EQ(estimate.size(), outcome.trajectory.size());
}

TEST(RunCommand, SyntheticIntegrationFollowsTheTruth) {
  const TempDir tmp;
  const fs::path dataset = tmp.path() / "dataset";
  testing::write_synthetic_dataset(dataset);
  const RunOutcome outcome = run(options_for(dataset, "integration", tmp.path() / "result"));
  ASSERT_TRUE(outcome.metrics.has_value());
  EXPECT_EQ(outcome.metrics->method, "integration");
  EXPECT_LT(outcome.metrics->errors.mean_m, 0.5);
}

TEST(RunCommand, ConfigSegmentsAppearInMetrics) {
  const TempDir tmp;
  const fs::path dataset = tmp.path() / "dataset";
  testing::write_synthetic_dataset(dataset);
  const std::string config = write_text(tmp.file("slam.yaml"),
                                        "segments:\n"
                                        "  second_half: [300, 600]\n"
                                        "  first_half: [0, 300]\n"
                                        "  after_the_end: [5000, 6000]\n");
  const RunOutcome outcome = run(options_for(dataset, "deadreckoning", tmp.path() / "out", config));
  ASSERT_TRUE(outcome.metrics.has_value());
  ASSERT_EQ(outcome.metrics->segments.size(), 3u);
  EXPECT_EQ(outcome.metrics->segments[0].first, "second_half");
  EXPECT_EQ(outcome.metrics->segments[1].first, "first_half");
  EXPECT_EQ(outcome.metrics->segments[2].first, "after_the_end");
  ASSERT_TRUE(outcome.metrics->segments[0].second.has_value());
  EXPECT_LT(*outcome.metrics->segments[0].second, 1.0);
  EXPECT_FALSE(outcome.metrics->segments[2].second.has_value());

  const std::string segments = json_segments(read_text(tmp.file("out/metrics.json")));
  const std::size_t second = segments.find("\"second_half\": ");
  const std::size_t first = segments.find("\"first_half\": ");
  ASSERT_NE(second, std::string::npos) << segments;
  ASSERT_NE(first, std::string::npos) << segments;
  EXPECT_LT(second, first) << segments;
  EXPECT_TRUE(json_value(segments, "first_half").has_value()) << segments;
  EXPECT_NE(segments.find("\"after_the_end\": null"), std::string::npos) << segments;
}

TEST(RunCommand, RerunWithoutTruthRemovesStaleMetrics) {
  const TempDir tmp;
  const fs::path out = tmp.path() / "out";
  testing::write_synthetic_dataset(tmp.path() / "with_truth");
  ASSERT_TRUE(run(options_for(tmp.path() / "with_truth", "deadreckoning", out)).metrics);
  ASSERT_TRUE(fs::exists(out / "metrics.json"));

  testing::SyntheticOptions no_truth;
  no_truth.write_truth = false;
  no_truth.duration_s = 60.0;
  testing::write_synthetic_dataset(tmp.path() / "without_truth", no_truth);
  const RunOutcome outcome = run(options_for(tmp.path() / "without_truth", "deadreckoning", out));
  EXPECT_FALSE(outcome.metrics.has_value());
  EXPECT_FALSE(fs::exists(out / "metrics.json"));
  // trajectory.tum is the new run's: 60 s long, not 600 s.
  const std::vector<io::TumPose> estimate = io::read_tum((out / "trajectory.tum").string());
  EXPECT_NEAR(estimate.back().t_s - estimate.front().t_s, 60.0, 1.0);
}

TEST(RunCommand, StPereDeadReckoningBeatsPlainIntegration) {
  MSISLAB_REQUIRE_STPERE();
  const TempDir tmp;
  const RunOutcome dr = run(options_for(testing::stpere_dir(), "deadreckoning", tmp.path() / "dr"));
  const RunOutcome integration =
      run(options_for(testing::stpere_dir(), "integration", tmp.path() / "integration"));
  ASSERT_TRUE(dr.metrics.has_value());
  ASSERT_TRUE(integration.metrics.has_value());
  std::printf("St. Pere mean error against GPS: deadreckoning %.3f m, integration %.3f m\n",
              dr.metrics->errors.mean_m, integration.metrics->errors.mean_m);
  EXPECT_EQ(dr.metrics->truth, "gps");
  EXPECT_EQ(integration.metrics->truth, "gps");
  EXPECT_LE(dr.metrics->errors.mean_m, integration.metrics->errors.mean_m);
  EXPECT_LT(dr.metrics->errors.mean_m, 3.8);
  EXPECT_TRUE(fs::is_regular_file(tmp.path() / "dr" / "metrics.json"));
}

// Expects run() to throw InputError containing every word, with nothing written to a fresh out.
void expect_rejected(const RunOptions& options, const std::vector<std::string>& words) {
  ASSERT_FALSE(fs::exists(options.out_dir)) << "the out dir must be fresh";
  try {
    run(options);
    ADD_FAILURE() << "no InputError";
  } catch (const io::InputError& e) {
    const std::string message = e.what();
    for (const std::string& word : words) {
      EXPECT_NE(message.find(word), std::string::npos) << message << "\nno '" << word << "'";
    }
  }
  EXPECT_FALSE(fs::exists(fs::path(options.out_dir) / "trajectory.tum"));
  EXPECT_FALSE(fs::exists(fs::path(options.out_dir) / "metrics.json"));
}

TEST(RunCommand, BadInputIsRejectedBeforeWriting) {
  const TempDir tmp;
  const fs::path good = tmp.path() / "good";
  testing::SyntheticOptions short_run;
  short_run.duration_s = 30.0;
  testing::write_synthetic_dataset(good, short_run);
  {
    SCOPED_TRACE("unknown method");
    expect_rejected(options_for(good, "magic", tmp.path() / "out1"), {"magic", "deadreckoning"});
  }
  {
    SCOPED_TRACE("missing dataset directory");
    const fs::path missing = tmp.path() / "no_such_dataset";
    expect_rejected(options_for(missing, "deadreckoning", tmp.path() / "out2"), {missing.string()});
  }
  {
    SCOPED_TRACE("a scenario given where a dataset goes");
    const std::string scenario = write_text(tmp.file("basin.yaml"), "seed: 1\n");
    expect_rejected(options_for(scenario, "deadreckoning", tmp.path() / "out2b"),
                    {scenario + ": is a file, not a dataset directory (a scenario?",
                     "msislab simulate " + scenario + " --out DIR"});
  }
  {
    SCOPED_TRACE("no DVL log");
    const fs::path no_dvl = tmp.path() / "no_dvl";
    testing::write_synthetic_dataset(no_dvl, short_run);
    fs::remove(no_dvl / "synth_DVL.log");
    expect_rejected(options_for(no_dvl, "deadreckoning", tmp.path() / "out3"),
                    {no_dvl.string(), "_DVL.log"});
  }
  {
    SCOPED_TRACE("truncated DVL log");
    const fs::path truncated = tmp.path() / "truncated";
    testing::write_synthetic_dataset(truncated, short_run);
    const std::string dvl = (truncated / "synth_DVL.log").string();
    const std::size_t line = testing::truncate_last_line(dvl);
    expect_rejected(options_for(truncated, "deadreckoning", tmp.path() / "out4"),
                    {dvl + ":" + std::to_string(line) + ":"});
  }
  {
    SCOPED_TRACE("config with an unknown key");
    const std::string config =
        write_text(tmp.file("bad.yaml"), "dead_reckoning:\n  dvl_sigma: 0.1\n");
    expect_rejected(options_for(good, "deadreckoning", tmp.path() / "out5", config),
                    {config + ":2:", "dead_reckoning.dvl_sigma"});
  }
  {
    SCOPED_TRACE("missing config file");
    const std::string config = tmp.file("absent.yaml");
    expect_rejected(options_for(good, "deadreckoning", tmp.path() / "out6", config), {config});
  }
}

}  // namespace
}  // namespace msislab::app
