// Line normals: a straight wall gets its normal, a corner's tip and isolated points get none.
#include "slam/line_normals.hpp"

#include <gtest/gtest.h>

#include <cmath>

namespace msislab {
namespace {

std::vector<ScanPoint> points_at(const std::vector<Eigen::Vector2d>& positions) {
  std::vector<ScanPoint> points(positions.size());
  for (std::size_t i = 0; i < positions.size(); ++i) points[i].p_m = positions[i];
  return points;
}

TEST(LineNormals, AWallGetsItsNormal) {
  std::vector<Eigen::Vector2d> wall;
  // A wall at 30 deg, sampled every 0.3 m, with a small zig-zag (5 cm) off the line.
  const Eigen::Vector2d along(std::cos(M_PI / 6.0), std::sin(M_PI / 6.0)),
      normal(-along.y(), along.x());
  for (int i = 0; i < 30; ++i) wall.push_back(0.3 * i * along + (i % 2 ? 0.05 : -0.05) * normal);
  const auto normals = line_normals(points_at(wall), LineNormalConfig{});
  for (const Eigen::Vector2d& n : normals) {
    ASSERT_NEAR(n.norm(), 1.0, 1e-12);
    EXPECT_GT(std::abs(n.dot(normal)), 0.999);
  }
}

TEST(LineNormals, CornersAndIsolatedPointsStayPointToPoint) {
  std::vector<Eigen::Vector2d> corner;
  for (int i = 0; i <= 10; ++i) corner.emplace_back(0.2 * i, 0.0);
  for (int i = 1; i <= 10; ++i) corner.emplace_back(0.0, 0.2 * i);
  corner.emplace_back(20.0, 20.0);  // alone: fewer than min_points neighbours
  const auto normals = line_normals(points_at(corner), LineNormalConfig{});
  EXPECT_EQ(normals[0], Eigen::Vector2d::Zero());  // the corner's tip
  EXPECT_EQ(normals.back(), Eigen::Vector2d::Zero());
  // Far from the tip (beyond the radius) the arms are lines.
  EXPECT_GT(std::abs(normals[10].y()), 0.999);
  EXPECT_GT(std::abs(normals[20].x()), 0.999);
}

}  // namespace
}  // namespace msislab
