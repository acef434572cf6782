// The beam's footprint in the measurement model (slam/beam_footprint.hpp): the table's lookup is
// exact on a function bilinear in range and incidence and clamped at the grid's edges; a wall
// whose points were reported beyond it by the table's offsets is put back on the wall; points
// without a line are kept; the spread goes into the reading noise along the beam's axis only.
#include "slam/beam_footprint.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "geometry/se2.hpp"

namespace msislab {
namespace {

constexpr double kDeg = M_PI / 180.0;

/// A table on ranges 5..45 m every 10 m and incidences 0..80 deg every 20 deg, its offset and
/// its standard deviation the given functions of (range, incidence) at the nodes.
template <class Offset, class Sd>
FootprintTable table_of(Offset offset, Sd sd) {
  FootprintTable t;
  for (double r = 5; r <= 45; r += 10) t.ranges_m.push_back(r);
  for (double a = 0; a <= 80; a += 20) t.incidences_rad.push_back(a * kDeg);
  for (const double r : t.ranges_m) {
    for (const double psi : t.incidences_rad) {
      t.offset_m.push_back(offset(r, psi));
      t.sd_m.push_back(sd(r, psi));
    }
  }
  return t;
}

TEST(BeamFootprint, LookupIsBilinearAndClampedAtTheEdges) {
  const auto f = [](double r, double psi) { return 0.1 + 0.01 * r - 0.3 * psi + 0.02 * r * psi; };
  const FootprintTable t = table_of(f, [](double, double) { return 0.2; });
  double offset_m = 0.0, sd_m = 0.0;
  for (const double r : {5.0, 12.3, 27.9, 44.0}) {
    for (const double psi : {0.0, 13.0 * kDeg, 41.0 * kDeg, 79.0 * kDeg}) {
      ASSERT_TRUE(footprint_offset(t, r, psi, offset_m, sd_m));
      EXPECT_NEAR(offset_m, f(r, psi), 1e-12) << r << " m, " << psi / kDeg << " deg";
      EXPECT_NEAR(sd_m, 0.2, 1e-12);
    }
  }
  // Beyond the grid: the nearest edge's figure.
  ASSERT_TRUE(footprint_offset(t, 60.0, 89.0 * kDeg, offset_m, sd_m));
  EXPECT_NEAR(offset_m, f(45.0, 80.0 * kDeg), 1e-12);
  ASSERT_TRUE(footprint_offset(t, 1.0, -0.1, offset_m, sd_m));
  EXPECT_NEAR(offset_m, f(5.0, 0.0), 1e-12);
  // The variances, not the deviations, are interpolated: halfway between sd 0 and 2, sqrt(2).
  FootprintTable steps = table_of([](double, double) { return 0.0; },
                                  [](double r, double) { return r < 20 ? 0.0 : 2.0; });
  ASSERT_TRUE(footprint_offset(steps, 20.0, 0.0, offset_m, sd_m));
  EXPECT_NEAR(sd_m, std::sqrt(2.0), 1e-12);
}

TEST(BeamFootprint, ACellWithoutAFigureLeavesItsNeighbourhoodAlone) {
  FootprintTable t =
      table_of([](double, double) { return 0.5; }, [](double, double) { return 0.1; });
  t.offset_m[2 * t.incidences_rad.size() + 1] =
      std::numeric_limits<double>::quiet_NaN();  // 25 m, 20 deg
  double offset_m = 0.0, sd_m = 0.0;
  EXPECT_FALSE(footprint_offset(t, 20.0, 10.0 * kDeg, offset_m, sd_m));
  EXPECT_FALSE(footprint_offset(t, 25.0, 20.0 * kDeg, offset_m, sd_m));
  EXPECT_TRUE(footprint_offset(t, 15.0, 10.0 * kDeg, offset_m, sd_m));  // its cells are whole
  EXPECT_TRUE(footprint_offset(t, 25.0, 40.0 * kDeg, offset_m, sd_m));  // on the next node
  EXPECT_FALSE(footprint_offset(FootprintTable{}, 20.0, 0.0, offset_m, sd_m));
}

/// A wall 12 m from the head, its normal turned 35 deg from the head's x axis, read by beams
/// every 1.8 deg (a 200-step revolution), each reporting the range on its axis plus
/// `offset(range, incidence)`; the head at (0.33, 0) in a scan frame turned 20 deg.
template <class Offset>
std::vector<ScanPoint> wall_read_beyond(Offset offset, Eigen::Vector2d& normal, double& d_m,
                                        Eigen::Vector2d& head_m) {
  const Pose2 beam_pose(1.0, -2.0, 20.0 * kDeg);
  const Eigen::Vector2d head_vehicle_m(0.33, 0.0);
  head_m = beam_pose.transform(head_vehicle_m);
  d_m = 12.0;
  normal = Eigen::Vector2d(std::cos(35.0 * kDeg), std::sin(35.0 * kDeg));
  std::vector<ScanPoint> points;
  for (double b = -50.0; b <= 50.0; b += 1.8) {
    const double bearing = 35.0 * kDeg + b * kDeg;
    const Eigen::Vector2d axis(std::cos(bearing), std::sin(bearing));
    const double psi = std::abs(b) * kDeg;
    const double axis_range_m = d_m / std::cos(psi);
    const double reported_m = axis_range_m + offset(axis_range_m, psi);
    ScanPoint p;
    p.p_sonar_m = head_m;
    p.p_m = head_m + reported_m * axis;
    p.p_vehicle_sonar_m = head_vehicle_m;
    p.p_vehicle_m = beam_pose.inverse().transform(p.p_m);
    p.cov_reading = 0.01 * Eigen::Matrix2d::Identity();
    p.cov = p.cov_reading;
    points.push_back(p);
  }
  return points;
}

TEST(BeamFootprint, AWallReadBeyondItIsPutBackOnIt) {
  // Offsets that grow with the incidence, as a strongest-bin detector's do (docs/simulator.md):
  // 0.3 m at normal incidence, 0.6 m at 45 deg.
  const auto offset = [](double, double psi) { return 0.3 + 0.6 * psi * psi / (M_PI / 2); };
  const FootprintTable t = table_of(offset, [](double, double) { return 0.25; });
  Eigen::Vector2d normal, head_m;
  double d_m = 0.0;
  std::vector<ScanPoint> points = wall_read_beyond(offset, normal, d_m, head_m);
  const std::vector<ScanPoint> before = points;
  const LineNormalConfig lines = FootprintConfig{}.line;  // 3 m, 3 points
  const FootprintCorrection c = correct_footprint(points, t, lines);
  EXPECT_EQ(c.corrected, points.size());
  EXPECT_EQ(c.no_line + c.no_cell, 0u);
  for (std::size_t k = 0; k < points.size(); ++k) {
    const double before_m = (before[k].p_m - head_m).dot(normal) - d_m;
    const double after_m = (points[k].p_m - head_m).dot(normal) - d_m;
    EXPECT_GT(before_m, 0.25) << k;
    // Left: the table's bilinear error between its 20-deg nodes and the incidence the read wall
    // shows (its offsets bend it a little), a few centimetres.
    EXPECT_LT(std::abs(after_m), 0.03) << k << ": " << before_m << " m before";
    // The point stays on its beam, in both frames.
    const Eigen::Vector2d ray = points[k].p_m - head_m, ray_before = before[k].p_m - head_m;
    EXPECT_NEAR(ray.normalized().dot(ray_before.normalized()), 1.0, 1e-12);
    const Eigen::Vector2d v = points[k].p_vehicle_m - points[k].p_vehicle_sonar_m;
    EXPECT_NEAR(v.norm(), ray.norm(), 1e-9);
    // The spread along the axis only: the larger of 0.01 and 0.25^2 along, 0.01 across.
    const Eigen::Vector2d axis = ray.normalized(), across(-axis.y(), axis.x());
    EXPECT_NEAR(axis.dot(points[k].cov_reading * axis), 0.0625, 1e-12);
    EXPECT_NEAR(across.dot(points[k].cov_reading * across), 0.01, 1e-12);
    EXPECT_NEAR(axis.dot(points[k].cov * axis), 0.0625, 1e-12);
  }
}

TEST(BeamFootprint, ASpreadBelowTheReadingsOwnLeavesItsNoise) {
  // The readings carry 0.1 m along and across; a table spread of 0.05 m adds nothing.
  const auto offset = [](double, double) { return 0.4; };
  const FootprintTable t = table_of(offset, [](double, double) { return 0.05; });
  Eigen::Vector2d normal, head_m;
  double d_m = 0.0;
  std::vector<ScanPoint> points = wall_read_beyond(offset, normal, d_m, head_m);
  const std::vector<ScanPoint> before = points;
  const LineNormalConfig lines = FootprintConfig{}.line;  // 3 m, 3 points
  ASSERT_EQ(correct_footprint(points, t, lines).corrected, points.size());
  for (std::size_t k = 0; k < points.size(); ++k) {
    EXPECT_TRUE(points[k].cov_reading.isApprox(before[k].cov_reading, 1e-12)) << k;
    EXPECT_TRUE(points[k].cov.isApprox(before[k].cov, 1e-12)) << k;
    EXPECT_NEAR((points[k].p_m - before[k].p_m).norm(), 0.4, 1e-9) << k;
  }
}

TEST(BeamFootprint, PointsWithoutALineAreKept) {
  const auto offset = [](double, double) { return 0.5; };
  const FootprintTable t = table_of(offset, [](double, double) { return 0.25; });
  Eigen::Vector2d normal, head_m;
  double d_m = 0.0;
  std::vector<ScanPoint> wall = wall_read_beyond(offset, normal, d_m, head_m);
  std::vector<ScanPoint> lone = {wall.front(), wall.back()};  // 6.5 m apart: no neighbours
  const std::vector<ScanPoint> before = lone;
  const FootprintCorrection c = correct_footprint(lone, t, LineNormalConfig{});
  EXPECT_EQ(c.corrected, 0u);
  EXPECT_EQ(c.no_line, 2u);
  for (std::size_t k = 0; k < lone.size(); ++k) {
    EXPECT_EQ(lone[k].p_m, before[k].p_m);
    EXPECT_EQ(lone[k].cov, before[k].cov);
  }
  // No table: nothing is looked at.
  const FootprintCorrection none = correct_footprint(wall, FootprintTable{}, LineNormalConfig{});
  EXPECT_EQ(none.corrected + none.no_line + none.no_cell, 0u);
}

TEST(BeamFootprint, ScanPointsCarryTheHeadOfTheirBeam) {
  SonarReading reading;
  reading.range_m = 10.0;
  reading.bearing_vehicle_rad = 0.5;
  reading.sigma_range_m = 0.1;
  reading.sigma_bearing_rad = 0.01;
  GaussianPose2 beam;
  beam.mean = Pose2(2.0, 1.0, 0.3);
  const Eigen::Vector2d head_vehicle_m(0.33, 0.1);
  std::vector<ScanPoint> points;
  add_scan_points({reading}, beam, head_vehicle_m, points, BeamDistortion{});
  ASSERT_EQ(points.size(), 1u);
  EXPECT_TRUE(points[0].p_sonar_m.isApprox(beam.mean.transform(head_vehicle_m), 1e-12));
  EXPECT_EQ(points[0].p_vehicle_sonar_m, head_vehicle_m);
  EXPECT_NEAR((points[0].p_m - points[0].p_sonar_m).norm(), 10.0, 1e-12);
}

}  // namespace
}  // namespace msislab
