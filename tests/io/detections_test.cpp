// The detections CSV reader and writer: exact round trips through .csv and .csv.gz, and the real
// St. Pere file (row count, first row and keyframe range from the dataset README).
#include "io/detections.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <random>

#include "io/input_error.hpp"
#include "test_support.hpp"

namespace msislab::io {
namespace {

using testing::TempDir;

std::vector<DetectionRecord> random_detections(std::size_t n, unsigned seed) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  std::vector<DetectionRecord> rows(n);
  std::int64_t beam_row = 0;
  for (std::size_t i = 0; i < n; ++i) {
    DetectionRecord& r = rows[i];
    beam_row += static_cast<std::int64_t>(rng() % 3);  // zero, one or many rows per beam
    r.keyframe = static_cast<std::int32_t>(1 + beam_row / 200);
    r.beam_row = beam_row;
    r.t_log_s = 1093455224.578 + 0.068 * static_cast<double>(beam_row) + 1e-3 * unit(rng);
    r.sensor_time_ms = 63224578 + 68 * beam_row;
    r.angle_idx = static_cast<std::int32_t>(199 - beam_row % 200);
    r.angle_rad = unit(rng) * 6.283185307179586;
    r.range_m = 1.0 + 49.0 * unit(rng);
  }
  rows.back().range_m = 19.4;
  rows.front().t_log_s = -0.0;
  return rows;
}

TEST(Detections, CsvRoundTripIsExact) {
  const TempDir dir;
  const auto rows = random_detections(5000, 1);
  write_detections(dir.file("x_detections.csv"), rows);
  EXPECT_EQ(read_detections(dir.file("x_detections.csv")), rows);
  const std::string text = testing::read_text(dir.file("x_detections.csv"));
  EXPECT_EQ(text.rfind("keyframe,beam_row,t_log_s,sensor_time_ms,angle_idx,angle_rad,range_m\n", 0),
            0u);
}

TEST(Detections, GzipRoundTripIsExactAndCompressed) {
  const TempDir dir;
  const auto rows = random_detections(120000, 2);  // > one 4 MiB read chunk, many flushes
  write_detections(dir.file("x_detections.csv.gz"), rows);
  const std::string bytes = testing::read_text(dir.file("x_detections.csv.gz"));
  ASSERT_GE(bytes.size(), 2u);
  EXPECT_EQ(static_cast<unsigned char>(bytes[0]), 0x1f) << "gzip magic";
  EXPECT_EQ(static_cast<unsigned char>(bytes[1]), 0x8b) << "gzip magic";
  EXPECT_EQ(read_detections(dir.file("x_detections.csv.gz")), rows);
}

TEST(Detections, ToleratesCrlfAndMissingFinalNewline) {
  const TempDir dir;
  const std::string path =
      testing::write_text(dir.file("crlf.csv"),
                          "keyframe,beam_row,t_log_s,sensor_time_ms,angle_idx,angle_rad,range_m\r\n"
                          "1,147,1093455234.723,63234722,199,6.251769,19.4\r\n\r\n"
                          "1,147,1093455234.723,63234722,199,6.251769,19.5");
  const auto rows = read_detections(path);
  ASSERT_EQ(rows.size(), 2u);
  EXPECT_EQ(rows[1].range_m, 19.5);
}

TEST(Detections, WriterRejectsNonFiniteAndUnorderedRows) {
  const TempDir dir;
  auto rows = random_detections(10, 3);
  rows[4].range_m = std::nan("");
  EXPECT_THROW(write_detections(dir.file("a.csv"), rows), InputError);
  rows = random_detections(10, 3);
  std::swap(rows[2].beam_row, rows[8].beam_row);
  EXPECT_THROW(write_detections(dir.file("b.csv.gz"), rows), InputError);
}

TEST(Detections, RealFile) {
  MSISLAB_REQUIRE_STPERE();
  const auto start = std::chrono::steady_clock::now();
  const auto rows = read_detections(testing::stpere_dir() + "/_040825_1735_detections.csv.gz");
  const std::chrono::duration<double> elapsed = std::chrono::steady_clock::now() - start;
  std::cout << "read " << rows.size() << " detections in " << elapsed.count() << " s\n";

  ASSERT_EQ(rows.size(), 1092064u);
  const DetectionRecord& first = rows.front();
  EXPECT_EQ(first.keyframe, 1);
  EXPECT_EQ(first.beam_row, 147);
  EXPECT_EQ(first.t_log_s, 1093455234.723);
  EXPECT_EQ(first.sensor_time_ms, 63234722);
  EXPECT_EQ(first.angle_idx, 199);
  EXPECT_EQ(first.angle_rad, 6.251769);
  EXPECT_EQ(first.range_m, 19.4);
  const auto [lowest, highest] = std::minmax_element(
      rows.begin(), rows.end(),
      [](const DetectionRecord& a, const DetectionRecord& b) { return a.keyframe < b.keyframe; });
  EXPECT_EQ(lowest->keyframe, 1);
  EXPECT_EQ(highest->keyframe, 230);
  EXPECT_TRUE(std::all_of(rows.begin(), rows.end(), [](const DetectionRecord& r) {
    return r.angle_idx >= 0 && r.angle_idx < 200 && r.range_m >= 1.0;
  }));
  EXPECT_EQ(rows.back().beam_row, 46146);
}

}  // namespace
}  // namespace msislab::io
