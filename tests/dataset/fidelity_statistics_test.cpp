// The fidelity statistics (eval/sonar_statistics) on samples and beams built by hand, with answers
// worked out on paper: band shares, runs, the checks of the detections file (io/detected_beams),
// and the per-beam, rotation and per-scan samples.
#include "dataset/detected_beams.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include "io/input_error.hpp"

namespace msislab::dataset {
namespace {

TEST(BandShares, SplitsAtBandEdgesAndKeepsTheTopInTheLastBand) {
  const std::vector<double> shares = band_shares({0.0, 5.0, 10.0, 19.9, 50.0}, 10.0, 5);
  ASSERT_EQ(shares.size(), 5u);
  EXPECT_DOUBLE_EQ(shares[0], 0.4);  // 0, 5
  EXPECT_DOUBLE_EQ(shares[1], 0.4);  // 10, 19.9
  EXPECT_DOUBLE_EQ(shares[2], 0.0);
  EXPECT_DOUBLE_EQ(shares[3], 0.0);
  EXPECT_DOUBLE_EQ(shares[4], 0.2);  // 50, the top edge
  EXPECT_EQ(band_shares({}, 10.0, 3), std::vector<double>(3, 0.0));
}

TEST(CountRuns, AGapOfOneMissingBinStartsARun) {
  EXPECT_EQ(count_runs({}, 0.1), 0);
  EXPECT_EQ(count_runs({1.0, 1.1, 1.2}, 0.1), 1);
  EXPECT_EQ(count_runs({1.0, 1.2}, 0.1), 2);  // bin 11 missing
  EXPECT_EQ(count_runs({1.0, 1.1, 1.3, 1.4, 2.0}, 0.1), 3);
  EXPECT_EQ(count_runs({1.2, 1.0, 1.1}, 0.1), 1);             // order does not matter
  EXPECT_EQ(count_runs({1.0, 1.0}, 0.1), 1);                  // a bin detected twice is one bin
  EXPECT_EQ(count_runs({0.30000000000000004, 0.4}, 0.1), 1);  // ranges round to bins
}

io::DetectionRecord row(std::int32_t keyframe, std::int64_t beam_row, std::int32_t angle_idx,
                        double range_m) {
  return {keyframe, beam_row, 0.0, 0, angle_idx, angle_idx * 2.0 * M_PI / 4.0, range_m};
}

/// Two keyframes of 4 beams (rows 0..3 and 4..7): 4 beams with detections, 4 empty.
std::vector<io::DetectionRecord> hand_rows() {
  return {row(1, 0, 3, 2.0), row(1, 0, 3, 2.1), row(1, 0, 3, 2.2),  // one run
          row(1, 2, 1, 5.0), row(1, 2, 1, 5.2), row(1, 2, 1, 7.0),  // three runs
          row(2, 4, 3, 3.0),                                        // angle 3 again
          row(2, 7, 0, 1.5), row(2, 7, 0, 1.6)};
}

TEST(GroupDetections, GroupsRowsByBeam) {
  const std::vector<DetectedBeam> beams = group_detections(hand_rows(), "d.csv", 8, 4, 50.0);
  ASSERT_EQ(beams.size(), 4u);
  EXPECT_EQ(beams[1].beam_row, 2);
  EXPECT_EQ(beams[1].keyframe, 1);
  EXPECT_EQ(beams[1].angle_idx, 1);
  EXPECT_EQ(beams[1].ranges_m, (std::vector<double>{5.0, 5.2, 7.0}));
  EXPECT_EQ(beams[3].ranges_m, (std::vector<double>{1.5, 1.6}));
}

void expect_rejected(const std::vector<io::DetectionRecord>& rows, std::size_t beam_count,
                     const std::string& what) {
  try {
    group_detections(rows, "x_detections.csv", beam_count, 4, 50.0);
    ADD_FAILURE() << "accepted; expected: " << what;
  } catch (const io::InputError& e) {
    const std::string message = e.what();
    EXPECT_EQ(message.rfind("x_detections.csv: ", 0), 0u) << message;
    EXPECT_NE(message.find(what), std::string::npos) << message << "\nexpected: " << what;
  }
}

TEST(GroupDetections, RejectsWhatTheStatisticsCannotCount) {
  std::vector<io::DetectionRecord> rows = hand_rows();
  expect_rejected(rows, 7, "data row 8 (beam_row 7): not a row of the beam times (7 beams)");
  rows[6].keyframe = 0;
  expect_rejected(rows, 8, "data row 7 (beam_row 4): keyframe 0 after keyframe 1");
  rows = hand_rows();
  rows[1].angle_idx = 2;
  expect_rejected(rows, 8, "data row 2 (beam_row 0): keyframe or angle_idx differs");
  rows = hand_rows();
  rows[6].keyframe = 1;  // keyframe 1 would span rows 0..4: five beams
  expect_rejected(rows, 8, "keyframe 1 spans beam rows 0..4, more than one revolution of 4 beams");
  rows = hand_rows();
  rows[2].range_m = 50.5;
  expect_rejected(rows, 8, "data row 3 (beam_row 0): range_m 50.5 outside the sonar range");
  rows = hand_rows();
  rows[7].keyframe = rows[8].keyframe = 3;  // keyframes 1..3: 12 beams
  expect_rejected(rows, 8,
                  "keyframes 1..3 make 12 beams of 4 per revolution, but the beam "
                  "times have 8");
}

TEST(SonarStatistics, CountsEveryBeamOfTheKeyframes) {
  const std::vector<DetectedBeam> beams = group_detections(hand_rows(), "d.csv", 10, 4, 50.0);
  std::vector<double> times_s;
  for (int i = 0; i < 10; ++i) times_s.push_back(10.0 + 0.5 * i);
  const SonarStatistics s = sonar_statistics(beams, times_s, 4, 0.1, 0.5);
  EXPECT_EQ(s.keyframes, 2);
  EXPECT_EQ(s.beams, 8u);
  EXPECT_EQ(s.empty_beams, 4u);
  EXPECT_EQ(s.bins_per_beam, (std::vector<double>{3, 3, 1, 2, 0, 0, 0, 0}));
  EXPECT_EQ(s.runs_per_beam, (std::vector<double>{1, 3, 1, 1, 0, 0, 0, 0}));
  EXPECT_EQ(s.first_ranges_m, (std::vector<double>{2.0, 5.0, 3.0, 1.5}));
  EXPECT_EQ(s.detected_ranges_m.size(), 9u);
  // Angle 3 is seen in keyframe 1 (row 0) and keyframe 2 (row 4): 4 beams, 2 s.
  EXPECT_EQ(s.beams_per_360, (std::vector<double>{4.0}));
  EXPECT_EQ(s.revolution_period_s, (std::vector<double>{2.0}));
  // No three consecutive beam rows have detections: no beam has an incidence.
  ASSERT_EQ(s.run_length_by_incidence_m.size(), static_cast<std::size_t>(kIncidenceBands));
  for (const std::vector<double>& band : s.run_length_by_incidence_m) EXPECT_TRUE(band.empty());
}

TEST(FirstRunLength, IsTheNearestRunsExtentInWholeBins) {
  EXPECT_EQ(first_run_length_m({}, 0.1), 0.0);
  EXPECT_NEAR(first_run_length_m({2.0}, 0.1), 0.1, 1e-12);
  // Bins 50, 51, 52 then a gap: the run 5.0..5.2 is 3 bins; the order of the rows does not matter.
  EXPECT_NEAR(first_run_length_m({7.0, 5.2, 5.0, 5.1, 7.1}, 0.1), 0.3, 1e-12);
  EXPECT_NEAR(first_run_length_m({5.0, 5.2}, 0.1), 0.1, 1e-12);  // one missing bin splits
}

TEST(IncidenceFromNeighbours, RecoversAFlatWallsIncidence) {
  // A flat wall 10 m away whose normal lies incidence_deg off the middle beam: r = d / cos(theta -
  // normal) at the three beams. The central difference is exact to about 0.1 deg here; ranges
  // rounded to 0.1 m bins (as detections are) move it by up to atan(0.1 / (2 r step)), under 10
  // deg, which the 15 deg bands of the statistic absorb.
  const double step_rad = 0.031415926535897934;
  for (const double incidence_deg : {0.0, 10.0, 30.0, 50.0, 65.0}) {
    const double normal_rad = incidence_deg * M_PI / 180.0;
    const auto range_m = [&](double theta_rad, bool rounded) {
      const double r = 10.0 / std::cos(theta_rad - normal_rad);
      return rounded ? std::round(10.0 * r) / 10.0 : r;
    };
    for (const bool rounded : {false, true}) {
      const double measured_deg = incidence_from_neighbours_deg(
          range_m(-step_rad, rounded), range_m(0.0, rounded), range_m(step_rad, rounded), step_rad);
      EXPECT_NEAR(measured_deg, incidence_deg, rounded ? 10.0 : 0.2) << incidence_deg;
    }
  }
  EXPECT_TRUE(std::isnan(incidence_from_neighbours_deg(10.0, 20.0, 20.5, step_rad)));  // an edge
  EXPECT_TRUE(std::isnan(incidence_from_neighbours_deg(20.0, 20.0, 23.5, step_rad)));
  EXPECT_TRUE(std::isnan(incidence_from_neighbours_deg(0.0, 0.0, 0.0, step_rad)));
}

TEST(SonarStatistics, BandsTheRunLengthByIncidence) {
  // Keyframe 1 of 4 beams: rows 0, 1, 2 see a wall at 20.0, 20.5, 21.0 m (incidence atan(1 /
  // (20.5 x 2 x 0.05)) = 26 deg for row 1); row 1's nearest run is 10 bins long.
  std::vector<io::DetectionRecord> rows = {row(1, 0, 0, 20.0)};
  for (int k = 0; k < 10; ++k) rows.push_back(row(1, 1, 1, 20.5 + 0.1 * k));
  rows.push_back(row(1, 1, 1, 30.0));  // a second run, not counted
  rows.push_back(row(1, 2, 2, 21.0));
  const std::vector<DetectedBeam> beams = group_detections(rows, "d.csv", 4, 4, 50.0);
  const SonarStatistics s = sonar_statistics(beams, std::vector<double>(4, 0.0), 4, 0.1, 0.05);
  ASSERT_EQ(s.run_length_by_incidence_m.size(), static_cast<std::size_t>(kIncidenceBands));
  EXPECT_TRUE(s.run_length_by_incidence_m[0].empty());
  ASSERT_EQ(s.run_length_by_incidence_m[1].size(), 1u);
  EXPECT_NEAR(s.run_length_by_incidence_m[1][0], 1.0, 1e-12);
}

TEST(SonarStatistics, PairsAnglesOnlyInConsecutiveKeyframes) {
  std::vector<io::DetectionRecord> rows = hand_rows();
  for (io::DetectionRecord& r : rows) {
    if (r.keyframe == 2) {
      r.keyframe = 3;
      r.beam_row += 4;  // rows 8 and 11: keyframe 2 has no detection
    }
  }
  const std::vector<DetectedBeam> beams = group_detections(rows, "d.csv", 12, 4, 50.0);
  const SonarStatistics s = sonar_statistics(beams, std::vector<double>(12, 0.0), 4, 0.1, 0.5);
  EXPECT_EQ(s.keyframes, 3);
  EXPECT_EQ(s.beams, 12u);
  EXPECT_EQ(s.empty_beams, 8u);
  EXPECT_TRUE(s.beams_per_360.empty());
}

TEST(ReadingsPerKeyframe, SumsTheReadingsOfEachKeyframesBeams) {
  const std::vector<DetectedBeam> beams = group_detections(hand_rows(), "d.csv", 8, 4, 50.0);
  std::vector<BeamReadings> readings(8);
  readings[0].readings.resize(1);
  readings[2].readings.resize(2);
  readings[3].readings.resize(5);  // no detections there: not counted
  readings[7].readings.resize(1);
  EXPECT_EQ(readings_per_keyframe(beams, readings), (std::vector<double>{3.0, 1.0}));
}

}  // namespace
}  // namespace msislab::dataset
