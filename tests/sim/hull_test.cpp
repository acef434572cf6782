// The sunken hull: a closed surface (every edge in exactly two triangles), normals out (positive
// enclosed volume, about the hull's) and its keel buried as placed.
#include "sim/hull.hpp"

#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <map>
#include <utility>

namespace msislab::sim {
namespace {

TEST(Hull, SectionsNarrowToAStem) {
  const HullShape hull;
  EXPECT_DOUBLE_EQ(half_beam_m(hull, -hull.length_m / 2.0), hull.beam_m / 2.0);
  EXPECT_NEAR(half_beam_m(hull, hull.length_m / 2.0), 0.0, 1e-12);
  const std::vector<Eigen::Vector3d> section = hull_section(hull, 0.0);
  ASSERT_EQ(section.size(), 5u);
  EXPECT_EQ(section[2], Eigen::Vector3d(0, 0, 0));  // the keel
  EXPECT_DOUBLE_EQ(section[0].y(), -section[4].y());
}

TEST(Hull, PlacedHullIsClosedOutwardAndBuried) {
  MeshBuilder builder;
  const std::uint32_t group = builder.group("hull", 0.8f, 0.4f);
  HullPlacement placement;
  placement.xy_m = {-25.0, -15.0};
  placement.yaw_deg = 35.0;
  placement.list_deg = 12.0;
  placement.buried_m = 0.3;
  placement.bottom_z_m = -6.0;
  add_hull(builder, HullShape{}, placement, group);
  const TriangleMesh& mesh = builder.mesh();
  ASSERT_GT(mesh.triangles.size(), 50u);

  std::map<std::pair<int, int>, int> edges;  // directed edge -> count
  double volume_m3 = 0.0;
  for (const Eigen::Vector3i& t : mesh.triangles) {
    for (int k = 0; k < 3; ++k) ++edges[{t[k], t[(k + 1) % 3]}];
    const Eigen::Vector3d a = mesh.vertices_m[t[0]].cast<double>(),
                          b = mesh.vertices_m[t[1]].cast<double>(),
                          c = mesh.vertices_m[t[2]].cast<double>();
    volume_m3 += a.dot(b.cross(c)) / 6.0;
  }
  for (const auto& [edge, count] : edges) {
    EXPECT_EQ(count, 1) << edge.first << "-" << edge.second;  // consistently oriented
    EXPECT_EQ(edges.count({edge.second, edge.first}), 1u) << edge.first << "-" << edge.second;
  }
  EXPECT_GT(volume_m3, 0.5 * 15.0 * 4.0 * 3.0 * 0.5);  // outward, and about the hull's size
  EXPECT_LT(volume_m3, 15.0 * 4.0 * 3.0);
  float z_lowest_m = 0.0f;
  for (const Eigen::Vector3f& v : mesh.vertices_m) z_lowest_m = std::min(z_lowest_m, v.z());
  EXPECT_NEAR(z_lowest_m, -6.3, 1e-5);
}

}  // namespace
}  // namespace msislab::sim
