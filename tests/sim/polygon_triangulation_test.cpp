// Tests of ear-clipping triangulation (sim/polygon_triangulation.hpp): convex, L-shaped, comb and
// star polygons and collinear vertices; and the self-crossing check. Every triangle must be
// counter-clockwise with positive area, the triangles must number n - 2 (fewer only with collinear
// vertices), and their areas must sum to the polygon's to 1e-9 (relative). Invalid input throws.
#include "sim/polygon_triangulation.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <stdexcept>
#include <vector>

namespace msislab::sim {
namespace {

using Polygon = std::vector<Eigen::Vector2d>;

double triangle_double_area(const Polygon& polygon, const Eigen::Vector3i& t) {
  return signed_double_area({polygon[t[0]], polygon[t[1]], polygon[t[2]]});
}

/// Checks the triangulation of a counter-clockwise polygon and returns its triangle count.
std::size_t check_triangulation(const Polygon& polygon) {
  const std::vector<Eigen::Vector3i> triangles = triangulate_polygon(polygon);
  const int n = static_cast<int>(polygon.size());
  double sum_double_area = 0.0;
  for (const Eigen::Vector3i& t : triangles) {
    for (int i = 0; i < 3; ++i) {
      EXPECT_GE(t[i], 0);
      EXPECT_LT(t[i], n);
    }
    const double double_area = triangle_double_area(polygon, t);
    EXPECT_GT(double_area, 0.0) << "triangle " << t.transpose() << " is not counter-clockwise";
    sum_double_area += double_area;
  }
  const double polygon_double_area = signed_double_area(polygon);
  EXPECT_NEAR(sum_double_area, polygon_double_area, 1e-9 * polygon_double_area);
  return triangles.size();
}

TEST(PolygonTriangulation, Square) {
  const Polygon square = {{0, 0}, {2, 0}, {2, 2}, {0, 2}};
  EXPECT_EQ(check_triangulation(square), 2u);
  EXPECT_DOUBLE_EQ(signed_double_area(square), 8.0);
}

TEST(PolygonTriangulation, SingleTriangle) {
  EXPECT_EQ(check_triangulation({{0, 0}, {1, 0}, {0, 1}}), 1u);
}

TEST(PolygonTriangulation, LShape) {
  const Polygon l_shape = {{0, 0}, {4, 0}, {4, 1}, {1, 1}, {1, 3}, {0, 3}};
  EXPECT_EQ(check_triangulation(l_shape), 4u);
}

TEST(PolygonTriangulation, ConcaveComb) {
  // A base 0 <= y <= 1 with five teeth of width 1 up to y = 4, gaps of width 1 between them.
  Polygon comb = {{0, 0}, {9, 0}};
  for (int tooth = 4; tooth >= 0; --tooth) {
    const double x_right = 2.0 * tooth + 1.0;
    const double x_left = 2.0 * tooth;
    comb.emplace_back(x_right, 4.0);
    comb.emplace_back(x_left, 4.0);
    if (tooth > 0) {
      comb.emplace_back(x_left, 1.0);
      comb.emplace_back(x_left - 1.0, 1.0);
    }
  }
  EXPECT_EQ(check_triangulation(comb), comb.size() - 2);
}

TEST(PolygonTriangulation, StarWithManyReflexVertices) {
  Polygon star;
  const int points = 12;
  for (int i = 0; i < 2 * points; ++i) {
    const double angle_rad = M_PI * i / points;
    const double radius_m = (i % 2 == 0) ? 10.0 : 3.0;
    star.emplace_back(radius_m * std::cos(angle_rad), radius_m * std::sin(angle_rad));
  }
  EXPECT_EQ(check_triangulation(star), star.size() - 2);
}

TEST(PolygonTriangulation, CollinearVerticesGiveNoZeroAreaTriangle) {
  const Polygon square_with_midpoints = {{0, 0}, {1, 0}, {2, 0}, {2, 1},  {2, 2},
                                         {1, 2}, {0, 2}, {0, 1}, {0, 0.5}};
  const std::size_t count = check_triangulation(square_with_midpoints);
  EXPECT_GE(count, 2u);
  EXPECT_LE(count, square_with_midpoints.size() - 2);
}

TEST(PolygonCrossings, SimplePolygonsHaveNone) {
  EXPECT_FALSE(find_crossing_edges({{0, 0}, {1, 0}, {1, 1}, {0, 1}}));
  EXPECT_FALSE(find_crossing_edges({{0, 0}, {4, 0}, {4, 1}, {1, 1}, {1, 3}, {0, 3}}));
  // Collinear but disjoint edges (the bottoms of a U) are not a crossing.
  EXPECT_FALSE(
      find_crossing_edges({{0, 0}, {3, 0}, {3, 2}, {2, 2}, {2, 1}, {1, 1}, {1, 2}, {0, 2}}));
}

TEST(PolygonCrossings, FindsABowTieAndATouchingVertex) {
  const auto bow_tie = find_crossing_edges({{0, 0}, {1, 1}, {1, 0}, {0, 1}});
  ASSERT_TRUE(bow_tie);
  EXPECT_EQ(*bow_tie, std::make_pair(0, 2));
  // Vertex 4 touches edge 0 (a pinched polygon).
  EXPECT_TRUE(find_crossing_edges({{0, 0}, {4, 0}, {4, 2}, {3, 2}, {2, 0}, {1, 2}, {0, 2}}));
}

TEST(PolygonTriangulation, RejectsInvalidInput) {
  EXPECT_THROW(triangulate_polygon({{0, 0}, {1, 0}}), std::invalid_argument);
  EXPECT_THROW(triangulate_polygon({{0, 0}, {0, 1}, {1, 1}, {1, 0}}), std::invalid_argument);
  EXPECT_THROW(triangulate_polygon({{0, 0}, {1, 0}, {2, 0}}), std::invalid_argument);
}

}  // namespace
}  // namespace msislab::sim
