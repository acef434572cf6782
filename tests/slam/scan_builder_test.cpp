// Scan building: a reading's point and covariance, motion compensation with a known motion (known
// points and covariances), and the motion between consecutive scan frames.
#include "slam/scan_builder.hpp"

#include <gtest/gtest.h>

namespace msislab {
namespace {

SonarReading reading(double t_s, double range_m, double bearing_rad) {
  return {t_s, range_m, bearing_rad, 0.1, 0.02};
}

GaussianPose2 step(double dx_m, const Eigen::Matrix3d& cov) { return {Pose2(dx_m, 0.0, 0.0), cov}; }

TEST(ScanBuilder, ReadingPointAndCovarianceInTheVehicleFrame) {
  const Eigen::Vector2d sonar(0.33, 0.0);
  const ScanPoint ahead = reading_in_vehicle(reading(0, 10.0, 0.0), sonar);
  EXPECT_TRUE(ahead.p_m.isApprox(Eigen::Vector2d(10.33, 0.0)));
  // Along the beam: sigma_r^2; across: (r sigma_b)^2 = (10 x 0.02)^2.
  EXPECT_NEAR(ahead.cov(0, 0), 0.01, 1e-12);
  EXPECT_NEAR(ahead.cov(1, 1), 0.04, 1e-12);
  EXPECT_NEAR(ahead.cov(0, 1), 0.0, 1e-12);
  const ScanPoint port = reading_in_vehicle(reading(0, 10.0, M_PI / 2), sonar);
  EXPECT_TRUE(port.p_m.isApprox(Eigen::Vector2d(0.33, 10.0)));
  EXPECT_NEAR(port.cov(0, 0), 0.04, 1e-12);
  EXPECT_NEAR(port.cov(1, 1), 0.01, 1e-12);
}

// The vehicle moves 1 m along x between beams, looking to port at a wall y = 10 (x along the wall).
// Beam i is taken 1 m x (i - centre) from the central pose: compensated, the points lie along the
// wall at those x; uncompensated, they would all pile up at x = 0.33.
TEST(ScanBuilder, KnownMotionGivesKnownPointsAndCovariances) {
  ScanBuilderConfig config;
  config.beams_per_scan = 5;
  ScanBuilder builder(config);
  const Eigen::Matrix3d step_cov = Eigen::Vector3d(0.01, 0.02, 0.001).asDiagonal();
  std::optional<Scan> scan;
  for (int i = 0; i < 5; ++i) {
    scan = builder.add_beam(i, step(1.0, step_cov), {reading(i, 10.0, M_PI / 2)});
    if (i < 4) {
      EXPECT_FALSE(scan);
    }
  }
  ASSERT_TRUE(scan);
  ASSERT_EQ(scan->points.size(), 5u);
  EXPECT_EQ(scan->t_s, 2.0);
  const Eigen::Matrix2d reading_cov = Eigen::Vector2d(0.04, 0.01).asDiagonal();
  for (int i = 0; i < 5; ++i) {
    const ScanPoint& p = scan->points[static_cast<std::size_t>(i)];
    EXPECT_NEAR(p.p_m.x(), 0.33 + (i - 2), 1e-12) << "beam " << i;
    EXPECT_NEAR(p.p_m.y(), 10.0, 1e-12) << "beam " << i;
  }
  // The central beam carries only the reading noise.
  EXPECT_TRUE(scan->points[2].cov.isApprox(reading_cov, 1e-12));
  // One beam later: the pose of beam 3 in the centre frame is d = N([1 0 0], S); its point
  // p = d (+) p_v has J_pose = [1 0 -p_y; 0 1 p_x] at yaw 0, with p_v = (0.33, 10).
  Matrix23d J;
  J << 1, 0, -10.0, 0, 1, 0.33;
  const Eigen::Matrix2d expected_3 = J * step_cov * J.transpose() + reading_cov;
  EXPECT_TRUE(scan->points[3].cov.isApprox(expected_3, 1e-12));
  // One beam earlier: x_c1 = (-)d with covariance J- S J-^T; at yaw 0, J- = [-1 0 0; 0 -1 -1; 0 0
  // -1] (x_ba = (-1, 0, 0): J- = [-1 0 y_ba; 0 -1 -x_ba; 0 0 -1]).
  Eigen::Matrix3d Jinv;
  Jinv << -1, 0, 0, 0, -1, 1, 0, 0, -1;
  const Eigen::Matrix3d P_c1 = Jinv * step_cov * Jinv.transpose();
  const Eigen::Matrix2d expected_1 = J * P_c1 * J.transpose() + reading_cov;
  EXPECT_TRUE(scan->points[1].cov.isApprox(expected_1, 1e-12));
  // Farther beams are less certain.
  EXPECT_GT(scan->points[4].cov.trace(), scan->points[3].cov.trace());
  EXPECT_GT(scan->points[0].cov.trace(), scan->points[1].cov.trace());
}

TEST(ScanBuilder, MotionBetweenScanFramesSpansOneRevolution) {
  ScanBuilderConfig config;
  config.beams_per_scan = 5;
  ScanBuilder builder(config);
  const Eigen::Matrix3d step_cov = Eigen::Vector3d(0.01, 0.02, 0.001).asDiagonal();
  std::vector<Scan> scans;
  for (int i = 0; i < 15; ++i) {
    if (auto scan = builder.add_beam(i, step(1.0, step_cov), {})) scans.push_back(*scan);
  }
  ASSERT_EQ(scans.size(), 3u);
  // First scan: from the first beam's pose to the centre (beam 2): 2 steps.
  EXPECT_NEAR(scans[0].motion.mean.x(), 2.0, 1e-12);
  // Then one revolution (5 beams) from centre to centre, with the covariance of 5 composed steps.
  GaussianPose2 five;
  for (int i = 0; i < 5; ++i) five = compose(five, step(1.0, step_cov));
  for (std::size_t k = 1; k < scans.size(); ++k) {
    EXPECT_NEAR(scans[k].motion.mean.x(), 5.0, 1e-12);
    EXPECT_NEAR(scans[k].t_s - scans[k - 1].t_s, 5.0, 1e-12);
    EXPECT_TRUE(scans[k].motion.cov.isApprox(five.cov, 1e-12));
  }
}

TEST(ScanBuilder, TurningVehicleCompensatesRotation) {
  // Turning on the spot by 0.1 rad per beam while every beam reads 10 m straight ahead: in the
  // centre frame the points lie on a circle of radius 10.33 at angles 0.1 (i - centre).
  ScanBuilderConfig config;
  config.beams_per_scan = 7;
  ScanBuilder builder(config);
  std::optional<Scan> scan;
  for (int i = 0; i < 7; ++i) {
    scan =
        builder.add_beam(i, {Pose2(0, 0, 0.1), Eigen::Matrix3d::Zero()}, {reading(i, 10.0, 0.0)});
  }
  ASSERT_TRUE(scan);
  for (int i = 0; i < 7; ++i) {
    const Eigen::Vector2d& p = scan->points[static_cast<std::size_t>(i)].p_m;
    EXPECT_NEAR(p.norm(), 10.33, 1e-9);
    EXPECT_NEAR(std::atan2(p.y(), p.x()), 0.1 * (i - 3), 1e-9);
  }
}

}  // namespace
}  // namespace msislab
