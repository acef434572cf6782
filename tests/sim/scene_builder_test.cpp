// sim/scene_builder: basins from outlines (walls only on wall edges, vertical or sloped) and
// prisms, checked for normals that face the water, closed prisms and the foot offset.
#include "sim/scene_builder.hpp"

#include <gtest/gtest.h>

#include <Eigen/Geometry>

namespace msislab::sim {
namespace {

Eigen::Vector3d normal_of(const TriangleMesh& mesh, std::size_t t) {
  const Eigen::Vector3d a = mesh.vertices_m[mesh.triangles[t][0]].cast<double>();
  const Eigen::Vector3d b = mesh.vertices_m[mesh.triangles[t][1]].cast<double>();
  const Eigen::Vector3d c = mesh.vertices_m[mesh.triangles[t][2]].cast<double>();
  return (b - a).cross(c - a);
}

Eigen::Vector3d centre_of(const TriangleMesh& mesh, std::size_t t) {
  Eigen::Vector3d sum = Eigen::Vector3d::Zero();
  for (int k = 0; k < 3; ++k) sum += mesh.vertices_m[mesh.triangles[t][k]].cast<double>();
  return sum / 3.0;
}

BasinOutline square(double side_m) {
  return {{{0.0, 0.0}, {side_m, 0.0}, {side_m, side_m}, {0.0, side_m}}, {true, true, true, true}};
}

TEST(SceneBuilder, BasinWallsFaceTheWaterAndTheBottomFacesUp) {
  MeshBuilder builder;
  const auto walls = builder.group("walls", 0.6f, 0.3f);
  const auto bottom = builder.group("bottom", 0.3f, 0.2f);
  add_basin(builder, square(10.0), {1.0, -3.0, 0.0}, walls, bottom);
  const TriangleMesh& mesh = builder.mesh();
  ASSERT_EQ(mesh.triangles.size(), 10u);  // 4 walls x 2 + bottom 2
  for (std::size_t t = 0; t < mesh.triangles.size(); ++t) {
    const Eigen::Vector3d n = normal_of(mesh, t);
    if (mesh.material_ids[t] == bottom) {
      EXPECT_GT(n.z(), 0.0);
    } else {
      const Eigen::Vector3d to_middle = Eigen::Vector3d(5.0, 5.0, 0.0) - centre_of(mesh, t);
      EXPECT_GT(n.head<2>().dot(to_middle.head<2>()), 0.0) << "wall triangle " << t;
    }
  }
}

TEST(SceneBuilder, OpenEdgesHaveNoWall) {
  BasinOutline outline = square(10.0);
  outline.wall_edge[1] = false;
  MeshBuilder builder;
  const auto walls = builder.group("walls", 0.6f, 0.3f);
  const auto bottom = builder.group("bottom", 0.3f, 0.2f);
  add_basin(builder, outline, {1.0, -3.0, 0.0}, walls, bottom);
  const TriangleMesh& mesh = builder.mesh();
  int wall_triangles = 0;
  for (std::size_t t = 0; t < mesh.triangles.size(); ++t) {
    if (mesh.material_ids[t] != walls) continue;
    ++wall_triangles;
    EXPECT_LT(centre_of(mesh, t).x(), 9.9) << "no wall along the open east edge";
  }
  EXPECT_EQ(wall_triangles, 6);
}

TEST(SceneBuilder, FootOffsetSlopesTheWallsIntoTheWater) {
  const std::vector<Eigen::Vector2d> foot = wall_foot_polygon(square(10.0), 1.0);
  ASSERT_EQ(foot.size(), 4u);
  EXPECT_NEAR((foot[0] - Eigen::Vector2d(1.0, 1.0)).norm(), 0.0, 1e-12);
  EXPECT_NEAR((foot[2] - Eigen::Vector2d(9.0, 9.0)).norm(), 0.0, 1e-12);
  BasinOutline open_east = square(10.0);
  open_east.wall_edge[1] = false;
  const std::vector<Eigen::Vector2d> half = wall_foot_polygon(open_east, 1.0);
  // Vertex 1 lies between the south wall and the open east edge: it moves off the wall only.
  EXPECT_NEAR((half[1] - Eigen::Vector2d(10.0, 1.0)).norm(), 0.0, 1e-12);
}

TEST(SceneBuilder, FootOffsetLongerThanAnEdgeStillGivesASimpleBottom) {
  BasinOutline notch = {
      {{0, 0}, {10, 0}, {10, 10}, {5.2, 10}, {5.2, 9}, {4.8, 9}, {4.8, 10}, {0, 10}},
      std::vector<bool>(8, true)};
  MeshBuilder builder;
  const auto walls = builder.group("walls", 0.6f, 0.3f);
  const auto bottom = builder.group("bottom", 0.3f, 0.2f);
  EXPECT_NO_THROW(add_basin(builder, notch, {1.0, -3.0, 2.0}, walls, bottom));
}

TEST(SceneBuilder, PrismIsClosedWithOutwardNormals) {
  MeshBuilder builder;
  const auto group = builder.group("clutter", 0.5f, 0.3f);
  add_prism(builder, {{0, 0}, {4, 0}, {4, 2}, {0, 2}}, -3.0, 0.5, group);
  const TriangleMesh& mesh = builder.mesh();
  ASSERT_EQ(mesh.triangles.size(), 12u);
  double volume_m3 = 0.0;  // divergence theorem: sum of a . (b x c) / 6
  for (std::size_t t = 0; t < mesh.triangles.size(); ++t) {
    const Eigen::Vector3d a = mesh.vertices_m[mesh.triangles[t][0]].cast<double>();
    const Eigen::Vector3d b = mesh.vertices_m[mesh.triangles[t][1]].cast<double>();
    const Eigen::Vector3d c = mesh.vertices_m[mesh.triangles[t][2]].cast<double>();
    volume_m3 += a.dot(b.cross(c)) / 6.0;
    const Eigen::Vector3d outward = centre_of(mesh, t) - Eigen::Vector3d(2.0, 1.0, -1.25);
    EXPECT_GT(normal_of(mesh, t).dot(outward), 0.0) << "triangle " << t;
  }
  EXPECT_NEAR(volume_m3, 4.0 * 2.0 * 3.5, 1e-4);
}

TEST(SceneBuilder, ChannelBasinIsASimpleBasinWithAnOpenFarEnd) {
  const ChannelBasin geometry;  // 60 m basin, 160 m x 16 m channel
  const BasinOutline outline = channel_basin_outline(geometry);
  ASSERT_EQ(outline.ccw_polygon_m.size(), 8u);
  ASSERT_EQ(outline.wall_edge.size(), 8u);
  // Shoelace area: the basin plus the channel, counter-clockwise (positive).
  double twice_area = 0.0;
  for (std::size_t i = 0; i < 8; ++i) {
    const Eigen::Vector2d& a = outline.ccw_polygon_m[i];
    const Eigen::Vector2d& b = outline.ccw_polygon_m[(i + 1) % 8];
    twice_area += a.x() * b.y() - b.x() * a.y();
  }
  EXPECT_NEAR(twice_area / 2.0, 60.0 * 60.0 + 160.0 * 16.0, 1e-9);
  MeshBuilder builder;
  const auto walls = builder.group("walls", 0.5f, 0.05f);
  const auto bottom = builder.group("bottom", 0.003f, 0.3f);
  add_basin(builder, outline, {1.0, -3.4, 0.0}, walls, bottom);
  const TriangleMesh& mesh = builder.mesh();
  double wall_length_m = 0.0;
  for (std::size_t t = 0; t < mesh.triangles.size(); ++t) {
    const Eigen::Vector3d n = normal_of(mesh, t);
    if (mesh.material_ids[t] == bottom) {
      EXPECT_GT(n.z(), 0.0);
      continue;
    }
    EXPECT_LT(centre_of(mesh, t).x(), 189.9) << "no wall across the channel's far end";
    wall_length_m += n.norm() / 2.0 / 4.4;  // area over height: two triangles per wall edge
    // Channel walls face the channel's axis.
    const Eigen::Vector3d c = centre_of(mesh, t);
    if (c.x() > 31.0) {
      EXPECT_LT(n.y() * c.y(), 0.0);
    }
  }
  // 60 + 22 + 160 (south), 160 + 22 + 60 (north) and 60 (west).
  EXPECT_NEAR(wall_length_m, 60.0 + 22.0 + 160.0 + 160.0 + 22.0 + 60.0 + 60.0, 1e-3);
  EXPECT_THROW(channel_basin_outline({60.0, 160.0, 60.0}), std::invalid_argument);
  EXPECT_THROW(channel_basin_outline({60.0, 0.0, 16.0}), std::invalid_argument);
}

TEST(SceneBuilder, OpenAreaHasTwoQuaysAndASparsePilingField) {
  const OpenArea geometry;  // 240 x 160 m, 24 pilings 15 m apart in x 30-200, y 30-140 m
  const BasinOutline outline = open_area_outline(geometry);
  ASSERT_EQ(outline.ccw_polygon_m.size(), 4u);
  EXPECT_EQ(outline.wall_edge, (std::vector<bool>{true, false, false, true}));
  EXPECT_TRUE(outline.ccw_polygon_m[2].isApprox(Eigen::Vector2d(240.0, 160.0)));

  const std::vector<Eigen::Vector2d> centres_m = open_area_pilings(geometry);
  ASSERT_EQ(centres_m.size(), 24u);
  for (std::size_t i = 0; i < centres_m.size(); ++i) {
    EXPECT_TRUE((centres_m[i].array() >= geometry.field_min_m.array()).all()) << i;
    EXPECT_TRUE((centres_m[i].array() <= geometry.field_max_m.array()).all()) << i;
    for (std::size_t j = 0; j < i; ++j) {
      EXPECT_GE((centres_m[i] - centres_m[j]).norm(), geometry.min_spacing_m) << i << " " << j;
    }
  }
  EXPECT_EQ(open_area_pilings(geometry), centres_m) << "the same seed, the same layout";
  OpenArea other = geometry;
  other.seed = 8;
  EXPECT_NE(open_area_pilings(other), centres_m);

  OpenArea crowded = geometry;
  crowded.pilings = 500;  // 500 x 15 m discs do not fit in 170 x 110 m
  EXPECT_THROW(open_area_pilings(crowded), std::invalid_argument);
  OpenArea outside = geometry;
  outside.field_max_m = {250.0, 140.0};
  EXPECT_THROW(open_area_outline(outside), std::invalid_argument);

  // A piling's footprint: counter-clockwise on its circle.
  const std::vector<Eigen::Vector2d> footprint_m = circle_footprint({5.0, 6.0}, 1.0, 12);
  ASSERT_EQ(footprint_m.size(), 12u);
  double twice_area = 0.0;
  for (std::size_t i = 0; i < 12; ++i) {
    EXPECT_NEAR((footprint_m[i] - Eigen::Vector2d(5.0, 6.0)).norm(), 1.0, 1e-12);
    const Eigen::Vector2d& a = footprint_m[i];
    const Eigen::Vector2d& b = footprint_m[(i + 1) % 12];
    twice_area += a.x() * b.y() - b.x() * a.y();
  }
  EXPECT_NEAR(twice_area / 2.0, 3.0, 1e-12);  // a regular 12-gon of unit radius: 3
}

}  // namespace
}  // namespace msislab::sim
