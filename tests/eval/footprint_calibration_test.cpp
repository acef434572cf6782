// The beam's footprint measured against truth (eval/footprint_calibration.hpp): samples from a
// scan's wall readings against the beams' axis hits, and the table of their mean and spread per
// cell (nearest node, readings far off their axis left out, thin cells without a figure).
#include "eval/footprint_calibration.hpp"

#include <gtest/gtest.h>

#include <cmath>

namespace msislab {
namespace {

constexpr double kDeg = M_PI / 180.0;

FootprintGrid grid_10_by_30() {
  FootprintGrid grid;
  grid.ranges_m = {10.0, 20.0, 30.0};
  grid.incidences_rad = {0.0, 30.0 * kDeg, 60.0 * kDeg};
  grid.min_samples = 3;
  grid.max_abs_offset_m = 2.0;
  return grid;
}

TEST(FootprintCalibration, EachCellTakesItsNearestSamplesMeanAndSpread) {
  std::vector<FootprintSample> samples = {
      // (20 m, 30 deg): offsets 0.2, 0.4, 0.9 -> mean 0.5, sd sqrt(0.13) (n - 1).
      {19.0, 25.0 * kDeg, 0.2},
      {24.9, 44.0 * kDeg, 0.4},
      {15.1, 16.0 * kDeg, 0.9},
      // (10 m, 0): two samples only, under min_samples 3.
      {9.0, 1.0 * kDeg, 0.3},
      {11.0, 2.0 * kDeg, 0.3},
      // Beyond the grid: the edge nodes (30 m, 60 deg), three alike.
      {48.0, 89.0 * kDeg, -0.5},
      {31.0, 70.0 * kDeg, -0.5},
      {60.0, 80.0 * kDeg, -0.5},
      // Off its axis by more than 2 m: left out.
      {20.0, 30.0 * kDeg, 2.5},
      {20.0, 30.0 * kDeg, -3.0},
  };
  const FootprintEstimate e = estimate_footprint(samples, grid_10_by_30());
  EXPECT_EQ(e.left_out, 2u);
  ASSERT_EQ(e.samples.size(), 9u);
  const std::size_t at_20_30 = 1 * 3 + 1, at_10_0 = 0, at_30_60 = 2 * 3 + 2;
  EXPECT_EQ(e.samples[at_20_30], 3);
  EXPECT_NEAR(e.table.offset_m[at_20_30], 0.5, 1e-12);
  EXPECT_NEAR(e.table.sd_m[at_20_30], std::sqrt(0.13), 1e-12);
  EXPECT_EQ(e.samples[at_10_0], 2);
  EXPECT_TRUE(std::isnan(e.table.offset_m[at_10_0]));
  EXPECT_TRUE(std::isnan(e.table.sd_m[at_10_0]));
  EXPECT_EQ(e.samples[at_30_60], 3);
  EXPECT_NEAR(e.table.offset_m[at_30_60], -0.5, 1e-12);
  EXPECT_NEAR(e.table.sd_m[at_30_60], 0.0, 1e-12);
  int total = 0;
  for (const int n : e.samples) total += n;
  EXPECT_EQ(total, 8);
}

/// A scan of a wall 12 m from the head (its normal along x), beams every 2 deg from -40 to 40,
/// each reading 0.4 m beyond the axis's hit; one beam a millisecond apart per reading.
PlacedScan wall_scan(std::vector<AxisTruth>& beams) {
  PlacedScan placed;
  for (int k = -20; k <= 20; ++k) {
    const double bearing = 2.0 * k * kDeg;
    const double axis_range_m = 12.0 / std::cos(bearing);
    ScanPoint p;
    p.t_s = 100.0 + 0.01 * (k + 20);
    p.p_sonar_m = Eigen::Vector2d(0.3, 0.0);
    p.p_m =
        p.p_sonar_m + (axis_range_m + 0.4) * Eigen::Vector2d(std::cos(bearing), std::sin(bearing));
    placed.scan.points.push_back(p);
    beams.push_back({p.t_s, axis_range_m, std::nullopt, std::nullopt});
  }
  return placed;
}

/// Lines as wide as the footprint's (3 m, 3 points): every reading of wall_scan lies on one.
LineNormalConfig wall_lines() {
  LineNormalConfig line;
  line.radius_m = 3.0;
  line.min_points = 3;
  return line;
}

TEST(FootprintCalibration, SamplesAreWallReadingsAgainstTheirAxisHit) {
  std::vector<AxisTruth> beams;
  const PlacedScan placed = wall_scan(beams);
  const LineNormalConfig line = wall_lines();
  const std::vector<FootprintSample> samples = footprint_samples({placed}, beams, line);
  ASSERT_EQ(samples.size(), placed.scan.points.size());
  for (std::size_t k = 0; k < samples.size(); ++k) {
    const double bearing = 2.0 * (static_cast<int>(k) - 20) * kDeg;
    EXPECT_NEAR(samples[k].offset_m, 0.4, 1e-9);
    EXPECT_NEAR(samples[k].range_m, 12.0 / std::cos(bearing) + 0.4, 1e-9);
    // The wall as read bends a little (0.4 m on 12-16 m): its normal within a degree.
    EXPECT_NEAR(samples[k].incidence_rad, std::abs(bearing), 1.0 * kDeg) << k;
  }
  // A reading whose beam the truth does not list, or whose axis met nothing, gives none.
  std::vector<AxisTruth> fewer = beams;
  fewer[3].first_hit_range_m.reset();
  fewer.erase(fewer.begin() + 10);
  EXPECT_EQ(footprint_samples({placed}, fewer, line).size(), placed.scan.points.size() - 2);
  // Nor does a point without a line (the matcher's stricter lines: 1.5 m, 5 points).
  EXPECT_LT(footprint_samples({placed}, beams, LineNormalConfig{}).size(),
            placed.scan.points.size());
}

// The bearing errors are taken from every reading near its beam's strongest echo (on a line or
// not), as the truth gives them; a reading more than 1 m from that echo, or whose beam has no
// strongest echo or no bearing (a dataset simulated before the column), gives none.
TEST(FootprintCalibration, BearingErrorsAreTheStrongestEchoesSourcesOffTheAxis) {
  std::vector<AxisTruth> beams;
  const PlacedScan placed = wall_scan(beams);  // readings 0.4 m beyond the axis hit
  for (std::size_t k = 0; k < beams.size(); ++k) {
    beams[k].strongest_range_m = *beams[k].first_hit_range_m + 0.4;
    beams[k].strongest_bearing_offset_rad = (k % 2 == 0 ? 3.0 : -3.0) * kDeg;
  }
  const std::vector<double> all = bearing_offsets_rad({placed}, beams);
  ASSERT_EQ(all.size(), beams.size());
  for (const double offset : all) EXPECT_NEAR(std::abs(offset), 3.0 * kDeg, 1e-12);
  std::vector<AxisTruth> fewer = beams;
  fewer[0].strongest_range_m = *fewer[0].strongest_range_m + 1.5;  // another echo than the reading
  fewer[1].strongest_bearing_offset_rad.reset();
  fewer[2].strongest_range_m.reset();
  fewer.erase(fewer.begin() + 10);
  EXPECT_EQ(bearing_offsets_rad({placed}, fewer).size(), beams.size() - 4);
}

// A wall reading's source off its axis is signed toward the wall's normal: on the wall x = 12
// seen at bearing b, a turn toward b = 0 lowers the incidence. Sources 1 deg from the axis
// toward the normal give +1 deg at every incidence, and the estimate's mean per incidence
// node is 1 deg; readings at b = 0 (no side) and those far from their strongest echo give none.
TEST(FootprintCalibration, WallBearingsAreSignedTowardTheNormal) {
  std::vector<AxisTruth> beams;
  const PlacedScan placed = wall_scan(beams);
  for (std::size_t k = 0; k < beams.size(); ++k) {
    const int step = static_cast<int>(k) - 20;  // bearing 2 step deg
    beams[k].strongest_range_m = *beams[k].first_hit_range_m + 0.4;
    beams[k].strongest_bearing_offset_rad = step > 0 ? -1.0 * kDeg : 1.0 * kDeg;
  }
  beams[3].strongest_range_m = *beams[3].strongest_range_m + 1.5;
  const LineNormalConfig line = wall_lines();
  const std::vector<FootprintSample> samples = footprint_samples({placed}, beams, line);
  ASSERT_EQ(samples.size(), placed.scan.points.size());
  for (std::size_t k = 0; k < samples.size(); ++k) {
    if (k == 3) {
      EXPECT_TRUE(std::isnan(samples[k].bearing_toward_normal_rad));
    } else if (k != 20) {
      EXPECT_NEAR(samples[k].bearing_toward_normal_rad, 1.0 * kDeg, 1e-12) << k;
    }
  }
  FootprintGrid grid = grid_10_by_30();
  grid.min_samples = 5;
  grid.max_abs_offset_m = 1.0;
  const FootprintEstimate e = estimate_footprint(samples, grid);
  // Bearings 0-14 deg go to the 0 node, 16-40 deg to the 30 deg node; none reach 60.
  EXPECT_EQ(e.bearing_samples[0] + e.bearing_samples[1], 40);
  EXPECT_NEAR(e.bearing_toward_normal_mean_rad[1], 1.0 * kDeg, 1e-12);
  EXPECT_NEAR(e.bearing_toward_normal_rms_rad[1], 1.0 * kDeg, 1e-12);
  EXPECT_TRUE(std::isnan(e.bearing_toward_normal_mean_rad[2]));
}

}  // namespace
}  // namespace msislab
