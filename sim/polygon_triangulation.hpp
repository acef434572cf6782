// Triangulation of a simple polygon by ear clipping (Eberly, "Triangulation by Ear Clipping"), for
// the flat bottoms and caps of the scene meshes, and the check that a polygon is simple. O(n^3) at
// worst: meant for a few hundred vertices.
#pragma once

#include <Eigen/Core>
#include <optional>
#include <utility>
#include <vector>

namespace msislab::sim {

/// Twice the signed area of a polygon (shoelace): > 0 when counter-clockwise.
double signed_double_area(const std::vector<Eigen::Vector2d>& polygon);

/// The first pair (i, j), i < j, of non-adjacent edges that cross or touch (edge i runs from vertex
/// i to i + 1); nullopt for a simple polygon. O(n^2).
std::optional<std::pair<int, int>> find_crossing_edges(const std::vector<Eigen::Vector2d>& polygon);

/// Triangles (indices into the polygon, each counter-clockwise) covering a simple
/// counter-clockwise polygon given without a repeated closing vertex: n - 2 of them. Collinear
/// vertices are allowed; one is dropped without a triangle only when no ear is left (e.g. the last
/// three vertices on a line), so no triangle has zero area. Throws std::invalid_argument for fewer
/// than 3 vertices, a clockwise or zero-area polygon, or when no ear can be found (a
/// self-intersecting polygon).
std::vector<Eigen::Vector3i> triangulate_polygon(const std::vector<Eigen::Vector2d>& ccw_polygon);

}  // namespace msislab::sim
