// The scenario generators' geometry: a square basin's outline, clearance and pulling waypoints
// inside, smoothing and Douglas-Peucker simplification of a track, and leg speeds timed to a
// real run.
#include "sim/scenario_path.hpp"

#include <gtest/gtest.h>

#include <stdexcept>

namespace msislab::sim {
namespace {

/// A 10 m square basin: its bottom two triangles (group "bottom") and four vertical wall quads
/// (group "walls") from (0, 0) to (10, 10).
TriangleMesh square_basin() {
  TriangleMesh mesh;
  mesh.group_names = {"bottom", "walls"};
  mesh.vertices_m = {{0, 0, -3}, {10, 0, -3}, {10, 10, -3}, {0, 10, -3},
                     {0, 0, 0},  {10, 0, 0},  {10, 10, 0},  {0, 10, 0}};
  mesh.triangles = {{0, 1, 2}, {0, 2, 3}};
  mesh.material_ids = {0, 0};
  for (int i = 0; i < 4; ++i) {
    const int j = (i + 1) % 4;
    mesh.triangles.emplace_back(i, j, j + 4);
    mesh.triangles.emplace_back(i, j + 4, i + 4);
    mesh.material_ids.insert(mesh.material_ids.end(), {1, 1});
  }
  mesh.materials.resize(2);
  return mesh;
}

TEST(ScenarioPath, OutlineInsideAndClearance) {
  const SceneOutline outline = outline_of(square_basin());
  EXPECT_EQ(outline.bottom.size(), 2u);
  EXPECT_TRUE(inside(outline, {5, 5}));
  EXPECT_TRUE(inside(outline, {0.1, 9.9}));
  EXPECT_FALSE(inside(outline, {-1, 5}));
  EXPECT_NEAR(clearance_m(outline, {5, 2}), 2.0, 1e-12);
  EXPECT_NEAR(clearance_m(outline, {12, 5}), -2.0, 1e-12);
  EXPECT_TRUE(nearest_wall_point(outline, {9, 4}).isApprox(Eigen::Vector2d(10, 4)));
  TriangleMesh no_walls = square_basin();
  no_walls.group_names = {"bottom", "clutter"};
  EXPECT_THROW(outline_of(no_walls), std::invalid_argument);
}

TEST(ScenarioPath, APathEntersAConvexPolygonWhereALegCrossesIt) {
  const Path2 box = {{10, 1}, {12, 1}, {12, 3}, {10, 3}};    // counter-clockwise
  EXPECT_TRUE(path_enters({{0, 2}, {20, 2}}, box));          // through it, no fix inside
  EXPECT_TRUE(path_enters({{11, 2}, {30, 30}}, box));        // starts inside
  EXPECT_FALSE(path_enters({{0, 0}, {20, 0}}, box));         // below it
  EXPECT_FALSE(path_enters({{0, 4}, {9, 4}, {9, 0}}, box));  // around a corner
  EXPECT_TRUE(path_enters({{0, 1}, {20, 1}}, box));          // along its edge
}

TEST(ScenarioPath, PullInsideGivesTheClearance) {
  const SceneOutline outline = outline_of(square_basin());
  Eigen::Vector2d near_wall(9.8, 5), outside(11, 3), clear(5, 5);
  EXPECT_GT(pull_inside(outline, near_wall, 1.0), 0.5);
  EXPECT_GE(clearance_m(outline, near_wall), 1.0);
  EXPECT_GT(pull_inside(outline, outside, 0.5), 1.0);
  EXPECT_GE(clearance_m(outline, outside), 0.5);
  EXPECT_EQ(pull_inside(outline, clear, 1.0), 0.0);
  EXPECT_EQ(clear, Eigen::Vector2d(5, 5));
  EXPECT_NEAR(min_leg_clearance_m(outline, {{2, 2}, {8, 2}, {8, 9}}), 1.0, 1e-9);
}

TEST(ScenarioPath, SmoothingKeepsTheEndsAndAverages) {
  const std::vector<double> t_s = {0, 1, 2, 3, 4};
  const Path2 p_m = {{0, 0}, {1, 1}, {2, 0}, {3, 1}, {4, 0}};
  const Path2 smoothed = smooth_track(t_s, p_m, 2.0);
  ASSERT_EQ(smoothed.size(), 5u);
  EXPECT_EQ(smoothed.front(), p_m.front());
  EXPECT_EQ(smoothed.back(), p_m.back());
  EXPECT_TRUE(smoothed[2].isApprox(Eigen::Vector2d(2, 2.0 / 3.0)));
  EXPECT_TRUE(smoothed[1].isApprox(Eigen::Vector2d(1, 1.0 / 3.0)));
}

TEST(ScenarioPath, DouglasPeuckerKeepsTheCorners) {
  const Path2 l_shape = {{0, 0}, {1, 0.01}, {2, 0}, {3, 0}, {3, 1}, {3.02, 2}, {3, 3}};
  EXPECT_EQ(simplify(l_shape, 0.1), (std::vector<std::size_t>{0, 3, 6}));
  EXPECT_EQ(simplify(l_shape, 0.001).size(), l_shape.size());
  EXPECT_DOUBLE_EQ(length_m({{0, 0}, {3, 4}, {3, 0}}), 9.0);
}

TEST(ScenarioPath, LegSpeedsReachTheWaypointsOnTime) {
  const Path2 path = {{0, 0}, {20, 0}, {20, 20}, {0, 20}};
  const std::vector<double> real_times_s = {0, 100, 150, 350};
  const auto [speeds_mps, arrivals_s] = timed_leg_speeds(path, real_times_s, 8);
  ASSERT_EQ(speeds_mps.size(), 3u);
  ASSERT_EQ(arrivals_s.size(), 4u);
  for (std::size_t k = 1; k < path.size(); ++k) {
    EXPECT_NEAR(arrivals_s[k], real_times_s[k], 3.0) << k;
  }
  EXPECT_GT(speeds_mps[1], speeds_mps[0]);  // the short second leg is the fast one
  EXPECT_GT(speeds_mps[0], speeds_mps[2]);
}

}  // namespace
}  // namespace msislab::sim
