// Scan points: a reading's point and covariance, and motion compensation with known beam poses
// (known points and covariances).
#include "slam/scan_builder.hpp"

#include <gtest/gtest.h>

namespace msislab {
namespace {

SonarReading reading(double t_s, double range_m, double bearing_rad) {
  return {t_s, range_m, bearing_rad, 0.1, 0.02};
}

TEST(ScanPoints, ReadingPointAndCovarianceInTheVehicleFrame) {
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
// Beam i is at 1 m x (i - c) from the central pose c = 2: compensated, the points lie along the
// wall at those x; uncompensated, they would all pile up at x = 0.33.
TEST(ScanPoints, KnownPosesGiveKnownPointsAndCovariances) {
  const Eigen::Vector2d sonar(0.33, 0.0);
  const Eigen::Matrix3d step_cov = Eigen::Vector3d(0.01, 0.02, 0.001).asDiagonal();
  // x_c3 = d = N([1 0 0], S); x_c1 = (-)d with covariance J- S J-^T; at yaw 0,
  // J- = [-1 0 y_ba; 0 -1 -x_ba; 0 0 -1] with x_ba = (-1, 0, 0).
  Eigen::Matrix3d Jinv;
  Jinv << -1, 0, 0, 0, -1, 1, 0, 0, -1;
  const std::vector<GaussianPose2> x_centre = {
      {Pose2(-2.0, 0.0, 0.0), 4.0 * step_cov},
      {Pose2(-1.0, 0.0, 0.0), Jinv * step_cov * Jinv.transpose()},
      {Pose2(), Eigen::Matrix3d::Zero()},
      {Pose2(1.0, 0.0, 0.0), step_cov},
      {Pose2(2.0, 0.0, 0.0), 2.0 * step_cov}};
  std::vector<ScanPoint> points;
  for (int i = 0; i < 5; ++i) {
    add_scan_points({reading(i, 10.0, M_PI / 2)}, x_centre[static_cast<std::size_t>(i)], sonar,
                    points);
  }
  ASSERT_EQ(points.size(), 5u);
  const Eigen::Matrix2d reading_cov = Eigen::Vector2d(0.04, 0.01).asDiagonal();
  for (int i = 0; i < 5; ++i) {
    const ScanPoint& p = points[static_cast<std::size_t>(i)];
    EXPECT_NEAR(p.p_m.x(), 0.33 + (i - 2), 1e-12) << "beam " << i;
    EXPECT_NEAR(p.p_m.y(), 10.0, 1e-12) << "beam " << i;
    EXPECT_TRUE(p.p_vehicle_m.isApprox(Eigen::Vector2d(0.33, 10.0))) << "beam " << i;
    EXPECT_EQ(p.t_s, i);
  }
  // The central beam carries only the reading noise.
  EXPECT_TRUE(points[2].cov.isApprox(reading_cov, 1e-12));
  // p = x (+) p_v has J_pose = [1 0 -p_y; 0 1 p_x] at yaw 0, with p_v = (0.33, 10).
  Matrix23d J;
  J << 1, 0, -10.0, 0, 1, 0.33;
  EXPECT_TRUE(points[3].cov.isApprox(J * step_cov * J.transpose() + reading_cov, 1e-12));
  const Eigen::Matrix3d P_c1 = Jinv * step_cov * Jinv.transpose();
  EXPECT_TRUE(points[1].cov.isApprox(J * P_c1 * J.transpose() + reading_cov, 1e-12));
  // Farther beams are less certain.
  EXPECT_GT(points[4].cov.trace(), points[3].cov.trace());
  EXPECT_GT(points[0].cov.trace(), points[1].cov.trace());
}

TEST(ScanPoints, TurningVehicleCompensatesRotation) {
  // Turned by 0.1 rad per beam while every beam reads 10 m straight ahead: in the centre frame the
  // points lie on a circle of radius 10.33 at angles 0.1 (i - centre).
  std::vector<ScanPoint> points;
  for (int i = 0; i < 7; ++i) {
    add_scan_points({reading(i, 10.0, 0.0)}, {Pose2(0, 0, 0.1 * (i - 3)), Eigen::Matrix3d::Zero()},
                    Eigen::Vector2d(0.33, 0.0), points);
  }
  ASSERT_EQ(points.size(), 7u);
  for (int i = 0; i < 7; ++i) {
    const Eigen::Vector2d& p = points[static_cast<std::size_t>(i)].p_m;
    EXPECT_NEAR(p.norm(), 10.33, 1e-9);
    EXPECT_NEAR(std::atan2(p.y(), p.x()), 0.1 * (i - 3), 1e-9);
  }
}

}  // namespace
}  // namespace msislab
