// Reading result files back (io/results and io/result_readers, as `msislab plot` does): what the
// writers write reads back, hand-written scans.csv and nees.csv parse, and malformed lines fail
// naming the file and line.
#include "results/result_readers.hpp"

#include <gtest/gtest.h>

#include <filesystem>
#include <stdexcept>

#include "io/input_error.hpp"
#include "io/text_lines.hpp"
#include "results/montecarlo_files.hpp"
#include "results/results.hpp"
#include "results/sweep_files.hpp"
#include "test_support.hpp"

namespace msislab::results {
namespace {

using testing::TempDir;
using testing::write_text;

/// Expects InputError whose message contains `part`.
template <typename Read>
void expect_error(Read read, const std::string& part) {
  try {
    read();
    FAIL() << "expected InputError containing '" << part << "'";
  } catch (const io::InputError& e) {
    EXPECT_NE(std::string(e.what()).find(part), std::string::npos) << e.what();
  }
}

constexpr const char* kScansHeader =
    "t_s,x_m,y_m,yaw_rad,cov_xx,cov_xy,cov_xyaw,cov_yy,cov_yyaw,cov_yawyaw,points\n";

TEST(TextLines, LastLinesOfAChildsStderr) {
  // A child process's stderr: CRLF or LF, blank lines skipped, the last ones in order; nothing
  // from a file that is not there.
  const TempDir tmp;
  const std::string path = write_text(tmp.file("stderr.log"), "one\r\n\ntwo\nthree\n\n");
  EXPECT_EQ(io::last_lines(path, 2), (std::vector<std::string>{"two", "three"}));
  EXPECT_EQ(io::last_lines(path, 5), (std::vector<std::string>{"one", "two", "three"}));
  EXPECT_EQ(io::last_line(path), "three");
  EXPECT_TRUE(io::last_lines(tmp.file("absent.log"), 3).empty());
  EXPECT_EQ(io::last_line(tmp.file("absent.log")), "");
}

TEST(ResultReaders, ScansCsvRowsAndSymmetricCovariance) {
  const TempDir tmp;
  const std::string path = write_text(tmp.file("scans.csv"), std::string(kScansHeader) +
                                                                 "10.5,1,2,0.3,4,0.5,0.1,9,0.2,"
                                                                 "0.01,120\r\n11,3,4,0.4,1,0,0,1,"
                                                                 "0,1,0\n");
  const std::vector<StampedPose> scans = read_scans_csv(path);
  ASSERT_EQ(scans.size(), 2u);
  EXPECT_EQ(scans[0].t_s, 10.5);
  EXPECT_EQ(scans[0].pose.mean.y(), 2.0);
  EXPECT_EQ(scans[1].pose.mean.x(), 3.0);
  Eigen::Matrix3d expected;
  expected << 4, 0.5, 0.1, 0.5, 9, 0.2, 0.1, 0.2, 0.01;
  EXPECT_EQ(scans[0].pose.cov, expected);
}

TEST(ResultReaders, ScansCsvErrorsNameFileAndLine) {
  const TempDir tmp;
  const std::string path = tmp.file("scans.csv");
  write_text(path, "t,x\n1,2\n");
  expect_error([&] { read_scans_csv(path); }, "scans.csv:1: wrong header");
  write_text(path, std::string(kScansHeader) + "1,0,0,0,1,0,0,1,0,1,3\n2,0,0,nan,1,0,0,1,0,1,3\n");
  expect_error([&] { read_scans_csv(path); }, "scans.csv:3: field 4 (yaw_rad)");
  write_text(path, std::string(kScansHeader) + "1,0,0,0,1,0,0,1,0,1,3.5\n");
  expect_error([&] { read_scans_csv(path); }, "scans.csv:2: field 11 (points)");
  write_text(path, std::string(kScansHeader) + "2,0,0,0,1,0,0,1,0,1,3\n1,0,0,0,1,0,0,1,0,1,3\n");
  expect_error([&] { read_scans_csv(path); }, "scans.csv:3: t_s goes backwards");
  write_text(path, "");
  expect_error([&] { read_scans_csv(path); }, "scans.csv: empty file");
  // A run that built no scan writes the header alone: zero scans, not an error.
  write_text(path, kScansHeader);
  EXPECT_TRUE(read_scans_csv(path).empty());
}

TEST(ResultReaders, PointsPlyRoundTrip) {
  const TempDir tmp;
  const std::vector<Eigen::Vector2d> points = {{1.5, -2.25}, {0.1, 1e-3}, {-40, 12.125}};
  write_points_ply(tmp.file("map.ply"), points);
  EXPECT_EQ(read_points_ply(tmp.file("map.ply")), points);
}

TEST(ResultReaders, PointsPlyErrors) {
  const TempDir tmp;
  const std::string path = tmp.file("map.ply");
  write_text(path, "ply\nformat binary_little_endian 1.0\nelement vertex 1\nend_header\n");
  expect_error([&] { read_points_ply(path); }, "no 'element vertex' with x and y properties");
  // Binary is read (one PLY reader for meshes and maps); cut short, it is an error.
  const std::string binary =
      "ply\nformat binary_little_endian 1.0\nelement vertex 2\nproperty float x\n"
      "property float y\nend_header\n";
  const float xy[3] = {1.5f, -2.0f, 3.0f};
  write_text(path, binary + std::string(reinterpret_cast<const char*>(xy), sizeof(xy)));
  expect_error([&] { read_points_ply(path); }, "header announces 2 vertices, the file has 1");
  const float xy2[4] = {1.5f, -2.0f, 3.0f, 0.25f};
  write_text(path, binary + std::string(reinterpret_cast<const char*>(xy2), sizeof(xy2)));
  EXPECT_EQ(read_points_ply(path), (std::vector<Eigen::Vector2d>{{1.5, -2.0}, {3.0, 0.25}}));
  write_text(path,
             "ply\nformat ascii 1.0\nelement vertex 3\nproperty double x\nproperty double y\n"
             "end_header\n1 2\n3 4\n");
  expect_error([&] { read_points_ply(path); }, "header announces 3 vertices, the file has 2");
  write_text(path,
             "ply\nformat ascii 1.0\nelement vertex 1\nproperty float x\nproperty float y\n"
             "property float z\nend_header\n1 2\n");
  expect_error([&] { read_points_ply(path); }, "map.ply:8: truncated line");
  write_text(path, "solid\n");
  expect_error([&] { read_points_ply(path); }, "not a PLY file");
}

TEST(ResultReaders, MetricsJsonWrittenByRunReadsBack) {
  const TempDir tmp;
  RunMetrics metrics;
  metrics.method = "worldcentric";
  metrics.truth = "simulation";
  metrics.segments = {{"loop", 1.5}, {"canal", std::nullopt}};
  metrics.anees = 3.2;
  metrics.diagnostics = {{"scan_candidates", 12}};
  write_metrics_json(tmp.file("metrics.json"), metrics, "/data/sim \"x\"");
  const StoredMetrics stored = read_metrics_json(tmp.file("metrics.json"));
  EXPECT_EQ(stored.metrics.method, "worldcentric");
  EXPECT_EQ(stored.metrics.truth, "simulation");
  EXPECT_EQ(stored.dataset_dir, "/data/sim \"x\"");
}

TEST(ResultReaders, MetricsJsonWithoutMethodIsAnError) {
  const TempDir tmp;
  write_text(tmp.file("metrics.json"), "{\"truth\": \"gps\"}\n");
  expect_error([&] { read_metrics_json(tmp.file("metrics.json")); }, "key 'method'");
  write_text(tmp.file("metrics.json"), "{\"method\": \"a\",\n\"truth\": [\n");
  expect_error([&] { read_metrics_json(tmp.file("metrics.json")); }, "metrics.json:3: ");
}

// calibration.csv: "t_s" then each parameter's name and name_sigma, a row per snapshot, numbers
// read back exactly; no snapshot, or snapshots whose parameters differ, are refused (nothing
// written).
TEST(ResultFiles, CalibrationCsv) {
  const TempDir dir;
  const std::string path = dir.file("calibration.csv");
  std::vector<CalibrationSnapshot> s = {
      {10.5, {{"range_scale", 0.98, 0.05}, {"dvl_scale", 1.0, 0.02}}},
      {24.3, {{"range_scale", 0.1 + 0.2, 0.0123456789012345}, {"dvl_scale", 1.01, 0.019}}}};
  write_calibration_csv(path, s);
  EXPECT_EQ(testing::read_text(path),
            "t_s,range_scale,range_scale_sigma,dvl_scale,dvl_scale_sigma\n"
            "10.5,0.98,0.05,1,0.02\n"
            "24.3,0.30000000000000004,0.0123456789012345,1.01,0.019\n");
  const std::string other = dir.file("other.csv");
  EXPECT_THROW(write_calibration_csv(other, {}), std::invalid_argument);
  s[1].estimates[1].name = "compass_deviation_cos_deg";
  EXPECT_THROW(write_calibration_csv(other, s), std::invalid_argument);
  s[1].estimates.pop_back();
  EXPECT_THROW(write_calibration_csv(other, s), std::invalid_argument);
  EXPECT_FALSE(std::filesystem::exists(other));
}

TEST(ResultReaders, NeesCsv) {
  const TempDir tmp;
  const std::string path = tmp.file("nees.csv");
  write_text(path,
             "method,scan,runs,mean_nees,lower,upper\nworldcentric,0,25,2.9,2.12,4.03\n"
             "deadreckoning,0,25,3.5,2.12,4.03\nworldcentric,1,25,3.1,2.12,4.03\n");
  const std::vector<NeesRow> rows = read_montecarlo_nees(path);
  ASSERT_EQ(rows.size(), 3u);
  EXPECT_EQ(rows[1].method, "deadreckoning");
  EXPECT_EQ(rows[2].scan, 1);
  EXPECT_EQ(rows[2].runs, 25);
  EXPECT_EQ(rows[2].mean_nees, 3.1);
  EXPECT_EQ(rows[2].upper, 4.03);

  write_text(path, "method,scan,runs,mean_nees,lower,upper\nworldcentric,0,0,2.9,2.12,4.03\n");
  expect_error([&] { read_montecarlo_nees(path); },
               "nees.csv:2: field 3 (runs) '0' is not a positive");
  write_text(path,
             "method,scan,runs,mean_nees,lower,upper\nwc,1,25,2.9,2.12,4.03\n"
             "wc,1,25,2.9,2.12,4.03\n");
  expect_error([&] { read_montecarlo_nees(path); },
               "nees.csv:3: field 2 (scan) '1' does not increase");
  write_text(path, "method,scan,nees\n");
  expect_error([&] { read_montecarlo_nees(path); }, "nees.csv:1: wrong header");
}

TEST(ResultReaders, SummaryJsonWrittenByMontecarloReadsBack) {
  const TempDir tmp;
  MethodSummary rc;
  rc.method = "robocentric";
  rc.runs = 48;
  rc.failed = 2;
  rc.failed_runs = {7, 31};
  rc.mean_error_m = 2.574;
  rc.mean_error_quantiles_m = std::array<double, 3>{1.25, 2.5, 4.75};
  rc.final_error_m = 3.5;
  rc.anees = 18.68;
  rc.nees_in_bounds_fraction = 0.072;
  rc.nees.resize(240);
  rc.segments = {{"loop", 1.2}, {"canal", std::nullopt}};
  rc.runtime_s = 212.5;
  MethodSummary dr;
  dr.method = "deadreckoning";
  dr.runs = 50;
  dr.paired = PairedDifference{"robocentric", 48, 1.25, 0.5, 1.1, 1.4, 3};
  const std::string path = tmp.file("summary.json");
  write_summary_json(path, {rc, dr});
  const std::vector<StoredSummary> stored = read_summary_json(path);
  ASSERT_EQ(stored.size(), 2u);
  EXPECT_EQ(stored[0].nees_scans, 240u);
  std::vector<MethodSummary> back;
  for (const StoredSummary& s : stored) back.push_back(s.summary);
  ASSERT_EQ(back.size(), 2u);
  EXPECT_EQ(back[0].method, "robocentric");
  EXPECT_EQ(back[0].runs, 48);
  EXPECT_EQ(back[0].failed, 2);
  EXPECT_EQ(back[0].failed_runs, (std::vector<int>{7, 31}));
  EXPECT_EQ(back[0].mean_error_m, 2.574);
  EXPECT_EQ(back[0].mean_error_quantiles_m, (std::array<double, 3>{1.25, 2.5, 4.75}));
  EXPECT_FALSE(back[1].mean_error_quantiles_m);
  EXPECT_EQ(back[0].final_error_m, 3.5);
  EXPECT_EQ(back[0].anees, 18.68);
  EXPECT_EQ(back[0].nees_in_bounds_fraction, 0.072);
  EXPECT_TRUE(back[0].nees.empty());
  ASSERT_EQ(back[0].segments.size(), 2u);
  EXPECT_EQ(back[0].segments[0], (std::pair<std::string, std::optional<double>>{"loop", 1.2}));
  EXPECT_FALSE(back[0].segments[1].second);
  EXPECT_EQ(back[0].runtime_s, 212.5);
  EXPECT_EQ(back[1].method, "deadreckoning");
  EXPECT_FALSE(back[1].anees);
  EXPECT_FALSE(back[1].mean_error_m);
  EXPECT_FALSE(back[0].paired);
  ASSERT_TRUE(back[1].paired);
  EXPECT_EQ(back[1].paired->reference, "robocentric");
  EXPECT_EQ(back[1].paired->runs, 48);
  EXPECT_EQ(back[1].paired->mean_m, 1.25);
  EXPECT_EQ(back[1].paired->sd_m, 0.5);
  EXPECT_EQ(back[1].paired->ci95_lower_m, 1.1);
  EXPECT_EQ(back[1].paired->ci95_upper_m, 1.4);
  EXPECT_EQ(back[1].paired->runs_lower, 3);

  write_text(path, "{}\n");
  expect_error([&] { read_summary_json(path); }, "summary.json: no method");
  write_text(path, "{\"rc\": {\"runs\": 1.5}}\n");
  expect_error([&] { read_summary_json(path); }, "key 'rc.runs'");
}

TEST(ResultReaders, RunErrorsCsvOncePerSecondFromTheFirstTruthStamp) {
  const TempDir tmp;
  const std::string path = tmp.file("errors.csv");
  std::vector<ErrorSample> errors;
  for (int i = 0; i <= 25; ++i) errors.push_back({100.0 + 0.1 * i, 0.01 * i});
  write_errors_csv(path, errors, 100.0);
  const std::vector<ErrorSample> back = read_errors_csv(path);
  ASSERT_EQ(back.size(), 3u);  // t = 0, 1, 2 s
  EXPECT_DOUBLE_EQ(back[1].t_s, 1.0);
  EXPECT_DOUBLE_EQ(back[1].error_m, 0.1);
  write_text(path, "t_s,error_m\n0,1\n0,2\n");
  EXPECT_THROW(read_errors_csv(path), io::InputError);
}

TEST(ResultReaders, ErrorSpreadAndHistogramCsvReadBack) {
  const TempDir tmp;
  MethodSummary s;
  s.method = "robocentric";
  s.error_spread = {{0.0, 3, 0.1, 0.0, 0.1, 0.2}, {1.0, 3, 0.5, 0.25, 0.5, 0.75}};
  s.pooled_errors_m = {0.1, 0.2, 0.3};
  write_error_spread_csv(tmp.file("errors.csv"), {s});
  const std::vector<ErrorSpreadRow> rows = read_error_spread_csv(tmp.file("errors.csv"));
  ASSERT_EQ(rows.size(), 2u);
  EXPECT_EQ(rows[1].method, "robocentric");
  EXPECT_EQ(rows[1].spread.runs, 3);
  EXPECT_EQ(rows[1].spread.p95_m, 0.75);
  write_error_histogram_csv(tmp.file("h.csv"), error_histograms({s}, 3));
  const std::vector<ErrorHistogram> h = read_error_histogram_csv(tmp.file("h.csv"));
  ASSERT_EQ(h.size(), 1u);
  EXPECT_EQ(h[0].fractions.size(), 3u);
  EXPECT_EQ(h[0].edges_m.back(), 0.3);
  // Bad rows: one error each, naming the file and line.
  for (const auto& [file, text] : std::vector<std::pair<std::string, std::string>>{
           {"errors.csv",
            "method,t_s,runs,mean_m,p05_m,p50_m,p95_m\na,1,3,1,1,1,1\na,1,3,1,1,1,1\n"},
           {"h.csv", "method,lower_m,upper_m,fraction\na,0,1,0.5\na,2,3,0.5\n"},
           {"h.csv", "method,lower_m,upper_m,fraction\na,0,1,1.5\n"}}) {
    write_text(tmp.file(file), text);
    try {
      if (file == "errors.csv") {
        read_error_spread_csv(tmp.file(file));
      } else {
        read_error_histogram_csv(tmp.file(file));
      }
      ADD_FAILURE() << text;
    } catch (const io::InputError& e) {
      EXPECT_NE(std::string(e.what()).find(tmp.file(file) + ":"), std::string::npos) << e.what();
    }
  }
}

TEST(ResultReaders, SweepCsvWithPairedColumnsReadsBack) {
  const TempDir tmp;
  SweepTable table;
  table.keys = {"scenario.sonar.revolution_s"};
  SweepRow rc;
  rc.cell = 0;
  rc.values = {"13.8"};
  rc.method = "robocentric";
  rc.runs = 20;
  rc.mean_error_m = 1.5;
  SweepRow wc = rc;
  wc.method = "worldcentric";
  wc.paired_reference = "robocentric";
  wc.paired_difference_m = 0.02;
  wc.paired_ci95_lower_m = -0.01;
  wc.paired_ci95_upper_m = 0.05;
  wc.paired_runs_lower = 7;
  table.rows = {rc, wc};
  const std::string path = tmp.file("sweep.csv");
  write_sweep_csv(path, table);
  const SweepTable back = read_sweep_csv(path);
  ASSERT_EQ(back.rows.size(), 2u);
  EXPECT_EQ(back.rows[0].paired_reference, "");
  EXPECT_FALSE(back.rows[0].paired_difference_m);
  EXPECT_EQ(back.rows[1].paired_reference, "robocentric");
  EXPECT_EQ(back.rows[1].paired_difference_m, 0.02);
  EXPECT_EQ(back.rows[1].paired_ci95_lower_m, -0.01);
  EXPECT_EQ(back.rows[1].paired_ci95_upper_m, 0.05);
  EXPECT_EQ(back.rows[1].paired_runs_lower, 7);
  // A reference without its figures is one error naming the file and line.
  const std::string text = io::read_whole_file(path);
  std::string corrupt = text;
  corrupt.replace(corrupt.rfind(",0.02,"), 6, ",,");
  write_text(path, corrupt);
  expect_error([&] { read_sweep_csv(path); }, "sweep.csv:3: the paired_ columns");
}

}  // namespace
}  // namespace msislab::results
