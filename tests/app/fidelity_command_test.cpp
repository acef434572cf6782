// `msislab fidelity` as a user runs it: two small detection datasets with statistics known by
// construction (tests/app/synthetic_detections.hpp), the printed table and fidelity.json against
// those numbers, --out complete (page, JSON, both figures), bad input exiting 2 with one line
// naming the file and leaving nothing behind, and the real St. Pere data against itself (skipped
// when the dataset is absent). --out draws with VTK: CMake runs this test under `xvfb-run -a`;
// msislab reruns itself under xvfb-run when it finds no display.
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <opencv2/core.hpp>
#include <opencv2/imgcodecs.hpp>
#include <string>

#include "cli_runner.hpp"
#include "io/json.hpp"
#include "synthetic_detections.hpp"
#include "test_support.hpp"

namespace msislab {
namespace {

namespace fs = std::filesystem;
using testing::CliResult;
using testing::DetectionPattern;
using testing::read_text;
using testing::run_msislab;
using testing::shell_quote;
using testing::TempDir;
using testing::write_detection_dataset;

/// Dataset "real": every other beam detected, first ranges 10..19 m. "sim": 3 beams in 4, first
/// ranges 11..20 m. Per keyframe of 200 beams: real 100 beams with 5 bins, 10 of them with 3 more
/// bins in a second run; sim 150 and 15.
class FidelityCommand : public ::testing::Test {
 protected:
  void SetUp() override {
    write_detection_dataset(real_);
    DetectionPattern sim;
    sim.prefix = "replica";
    sim.period = 4;
    sim.detected_per_period = 3;
    sim.first_m = 11.0;
    sim_detections_ = write_detection_dataset(sim_, sim);
  }

  CliResult fidelity(const std::string& extra = "") const {
    return run_msislab(
        "fidelity " + shell_quote(real_.string()) + " " + shell_quote(sim_.string()) + extra, tmp_);
  }

  TempDir tmp_;
  fs::path real_ = tmp_.path() / "real";
  fs::path sim_ = tmp_.path() / "sim";
  fs::path out_ = tmp_.path() / "report";
  std::string sim_detections_;
};

/// The row with this key in fidelity.json.
io::JsonObject row(const io::Json& json, const std::string& key) {
  for (const io::Json& item : json.at("rows")) {
    const io::JsonObject r(item, "fidelity.json");
    if (r.string("key") == key) return r;
  }
  throw std::runtime_error("no row " + key);
}

/// The values to 1e-6 (beam times near 1e9 s carry about 1e-7 s), the ratio, null when real is 0.
void expect_row(const io::Json& json, const std::string& key, double real, double sim) {
  SCOPED_TRACE(key);
  const io::JsonObject r = row(json, key);
  EXPECT_NEAR(r.number("real"), real, 1e-6);
  EXPECT_NEAR(r.number("sim"), sim, 1e-6);
  if (real == 0.0) {
    EXPECT_EQ(r.number_or_null("ratio"), std::nullopt);
  } else {
    EXPECT_NEAR(r.number("ratio"), sim / real, 1e-6);
  }
}

void expect_one_error_line(const CliResult& result, const std::string& part) {
  EXPECT_EQ(result.exit_code, 2) << result.out;
  EXPECT_EQ(std::count(result.err.begin(), result.err.end(), '\n'), 1) << result.err;
  EXPECT_EQ(result.err.rfind("msislab: ", 0), 0u) << result.err;
  EXPECT_NE(result.err.find(part), std::string::npos) << result.err << "expected: " << part;
}

void expect_png(const fs::path& path, int width, int height) {
  SCOPED_TRACE(path.string());
  const cv::Mat image = cv::imread(path.string(), cv::IMREAD_COLOR);
  ASSERT_FALSE(image.empty()) << "missing or not decodable";
  EXPECT_EQ(image.cols, width);
  EXPECT_EQ(image.rows, height);
  EXPECT_LT(cv::mean(image)[0], 254.0) << "blank";
}

TEST_F(FidelityCommand, PrintsTheTableOfKnownStatistics) {
  const CliResult result = fidelity();
  ASSERT_EQ(result.exit_code, 0) << result.err;
  EXPECT_EQ(result.err, "");
  for (const char* line : {
           "| beams with no detection (%) | 50.0 | 25.0 | 0.50 |  |",
           "| runs of consecutive bins per beam, mean | 0.550 | 0.825 | 1.50 |  |",
           "| beams with 2 or more runs (%) | 5.00 | 7.50 | 1.50 |  |",
           "| first detected range, median (m) | 14.50 | 15.50 | 1.07 | 0.100 |",
           "| first ranges at 10-20 m (%) | 100.0 | 90.0 | 0.90 |  |",
           "| points per scan, mean | 100.0 | 150.0 | 1.50 |  |",
           "| beams per 360 deg, median | 200.0 | 200.0 | 1.00 |  |",
           "| revolution period, median (s) | 13.80 | 13.80 | 1.00 |  |",
       }) {
    EXPECT_NE(result.out.find(std::string("\n") + line + "\n"), std::string::npos) << line << "\n"
                                                                                   << result.out;
  }
  EXPECT_NE(result.out.find("\n| detected bins per beam, mean | 2.65 | "), std::string::npos);
  EXPECT_FALSE(fs::exists(out_));
}

TEST_F(FidelityCommand, OutWritesPageJsonAndFigures) {
  const CliResult result = fidelity(" --out " + shell_quote(out_.string()));
  ASSERT_EQ(result.exit_code, 0) << result.err;
  EXPECT_NE(result.out.find("wrote " + (out_ / "fidelity.md").string() + "\n"), std::string::npos)
      << result.out;
  const io::Json json = io::read_json_file((out_ / "fidelity.json").string());
  expect_row(json, "empty_beams_percent", 50.0, 25.0);
  expect_row(json, "bins_per_beam_mean", 2.65, 3.975);
  expect_row(json, "runs_per_beam_mean", 0.55, 0.825);
  expect_row(json, "multi_run_beams_percent", 5.0, 7.5);
  expect_row(json, "first_range_median_m", 14.5, 15.5);
  EXPECT_NEAR(row(json, "first_range_median_m").number("ks"), 0.1, 1e-12);
  EXPECT_EQ(row(json, "first_range_p10_m").number_or_null("ks"), std::nullopt);
  expect_row(json, "first_ranges_20_30_m_percent", 0.0, 10.0);
  expect_row(json, "points_per_scan_p90", 100.0, 150.0);
  expect_row(json, "revolution_period_s", 13.8, 13.8);
  const io::JsonObject real(json.at("real"), "fidelity.json");
  EXPECT_EQ(real.number("beams"), 5 + 600 + 3);
  EXPECT_EQ(real.number("beams_counted"), 600);
  EXPECT_EQ(real.number("revolution_drawn"), 2);

  const std::string page = read_text((out_ / "fidelity.md").string());
  for (const std::string part :
       {"# Simulator fidelity: sim against real", "Generated by `msislab fidelity ",
        "| **Per beam** | | | | |", "## How each statistic is computed",
        "Beams outside every keyframe", "](figures/ranges.png)", "](figures/revolution.png)"}) {
    EXPECT_NE(page.find(part), std::string::npos) << part;
  }
  expect_png(out_ / "figures" / "ranges.png", 2200, 900);
  expect_png(out_ / "figures" / "revolution.png", 1800, 900);
  std::vector<std::string> names;
  for (const auto& e : fs::directory_iterator(tmp_.path()))
    names.push_back(e.path().filename().string());
  std::sort(names.begin(), names.end());
  EXPECT_EQ(names, (std::vector<std::string>{"real", "report", "sim", "stderr.txt", "stdout.txt"}))
      << "no scratch folder left behind";
}

TEST_F(FidelityCommand, OutReplacesAnEarlierReportButNoOtherFolder) {
  ASSERT_EQ(fidelity(" --out " + shell_quote(out_.string())).exit_code, 0);
  const CliResult again =
      fidelity(" --out " + shell_quote(out_.string()) + " --revolution-real 1 --revolution-sim 3");
  ASSERT_EQ(again.exit_code, 0) << again.err;
  const io::Json json = io::read_json_file((out_ / "fidelity.json").string());
  EXPECT_EQ(io::JsonObject(json.at("sim"), "f").number("revolution_drawn"), 3);
  EXPECT_NE(read_text((out_ / "fidelity.md").string()).find("--revolution-sim 3"),
            std::string::npos);

  testing::write_text((out_ / "notes.txt").string(), "mine");
  expect_one_error_line(fidelity(" --out " + shell_quote(out_.string())), "notes.txt");
  EXPECT_EQ(read_text((out_ / "notes.txt").string()), "mine");
}

TEST_F(FidelityCommand, RevolutionOutsideTheKeyframes) {
  const CliResult result = fidelity(" --out " + shell_quote(out_.string()) + " --revolution-sim 4");
  expect_one_error_line(result,
                        sim_detections_ + ": --revolution-sim 4: the keyframes here are 1..3");
  EXPECT_FALSE(fs::exists(out_));
}

TEST_F(FidelityCommand, MissingDirectory) {
  const std::string missing = (tmp_.path() / "nowhere").string();
  const CliResult result =
      run_msislab("fidelity " + shell_quote(real_.string()) + " " + shell_quote(missing) +
                      " --out " + shell_quote(out_.string()),
                  tmp_);
  expect_one_error_line(result, missing + ": dataset directory does not exist");
  EXPECT_FALSE(fs::exists(out_));
}

TEST_F(FidelityCommand, NoDetectionsFile) {
  fs::remove(sim_detections_);
  expect_one_error_line(fidelity(" --out " + shell_quote(out_.string())),
                        sim_.string() + ": no *_detections.csv[.gz] file");
  EXPECT_FALSE(fs::exists(out_));
}

TEST_F(FidelityCommand, NoBeamTimes) {
  fs::remove(real_ / "synth_IS_timestamps.log");
  expect_one_error_line(fidelity(), real_.string() + ": no *_IS_timestamps.log file");
}

TEST_F(FidelityCommand, TruncatedDetections) {
  const std::string bytes = read_text(sim_detections_);
  testing::write_text(sim_detections_, bytes.substr(0, bytes.size() / 2));
  expect_one_error_line(fidelity(" --out " + shell_quote(out_.string())),
                        sim_detections_ + ": truncated gzip data");
  EXPECT_FALSE(fs::exists(out_));
}

TEST_F(FidelityCommand, MalformedDetectionsRow) {
  fs::remove(sim_detections_);
  const std::string csv = (sim_ / "replica_detections.csv").string();
  testing::write_text(csv,
                      "keyframe,beam_row,t_log_s,sensor_time_ms,angle_idx,angle_rad,range_m\n"
                      "1,5,1000000000.345,345,199,6.25,10\n"
                      "1,5,1000000000.345,345,199,6.25\n");
  expect_one_error_line(fidelity(), csv + ":3:");
}

TEST_F(FidelityCommand, DetectionsBeyondTheBeamTimes) {
  fs::remove(sim_detections_);
  const std::string csv = (sim_ / "replica_detections.csv").string();
  testing::write_text(csv,
                      "keyframe,beam_row,t_log_s,sensor_time_ms,angle_idx,angle_rad,range_m\n"
                      "1,5000,1000000000.345,345,199,6.25,10\n");
  expect_one_error_line(fidelity(), csv + ": data row 1 (beam_row 5000): not a row of the beam");
}

TEST_F(FidelityCommand, MismatchedSetups) {
  const std::string setup = (sim_ / "replica_SETUP.log").string();
  testing::write_text(setup, "30 0.1 0.0314159\n");
  const CliResult result = fidelity(" --out " + shell_quote(out_.string()));
  expect_one_error_line(result, setup + ": sonar setup (range 30 m");
  EXPECT_NE(result.err.find("differs from " + (real_ / "synth_SETUP.log").string()),
            std::string::npos)
      << result.err;
  EXPECT_FALSE(fs::exists(out_));
}

// The real dataset against itself: every ratio 1 and every KS distance 0.
TEST(FidelityRealData, StPereAgainstItself) {
  MSISLAB_REQUIRE_STPERE();
  const TempDir tmp;
  const fs::path out = tmp.path() / "self";
  const CliResult result =
      run_msislab("fidelity " + shell_quote(testing::stpere_dir()) + " " +
                      shell_quote(testing::stpere_dir()) + " --out " + shell_quote(out.string()),
                  tmp);
  ASSERT_EQ(result.exit_code, 0) << result.err;
  const io::Json json = io::read_json_file((out / "fidelity.json").string());
  const io::JsonObject real(json.at("real"), "fidelity.json");
  EXPECT_EQ(real.number("beams"), 46259);
  EXPECT_EQ(real.number("beams_counted"), 46000);  // 230 keyframes of 200 beams
  EXPECT_EQ(real.number("detected_bins"), 1092064);
  for (const io::Json& item : json.at("rows")) {
    const io::JsonObject r(item, "fidelity.json");
    SCOPED_TRACE(r.string("key"));
    const std::optional<double> ratio = r.number_or_null("ratio");
    if (r.number("real") != 0.0) {
      EXPECT_EQ(ratio, 1.0);
    }
    if (const std::optional<double> ks = r.number_or_null("ks")) {
      EXPECT_EQ(*ks, 0.0);
    }
  }
  // The per-beam figures of docs/fidelity.md as tools/fidelity_crosscheck.py prints them;
  // fidelity_crosscheck_test holds every sonar row to that script (it fails without python3).
  EXPECT_NEAR(row(json, "empty_beams_percent").number("real"), 40.309, 1e-3);
  EXPECT_NEAR(row(json, "bins_per_beam_mean").number("real"), 23.7405, 1e-4);
  EXPECT_NEAR(row(json, "runs_per_beam_mean").number("real"), 0.63783, 1e-5);
  EXPECT_NEAR(row(json, "multi_run_beams_percent").number("real"), 2.8957, 1e-4);
  EXPECT_NEAR(row(json, "first_range_p10_m").number("real"), 11.6, 1e-9);
  EXPECT_NEAR(row(json, "first_range_median_m").number("real"), 21.4, 1e-9);
  EXPECT_NEAR(row(json, "first_range_p90_m").number("real"), 39.9, 1e-9);
  EXPECT_NEAR(row(json, "revolution_period_s").number("real"), 13.8, 0.05);
  EXPECT_EQ(row(json, "beams_per_revolution").number("real"), 200.0);
}

}  // namespace
}  // namespace msislab
