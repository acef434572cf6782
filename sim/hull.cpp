#include "sim/hull.hpp"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>

#include "sim/polygon_triangulation.hpp"

namespace msislab::sim {

double half_beam_m(const HullShape& hull, double x_m) {
  const double bow_start_m = -hull.length_m / 2.0 + hull.parallel_fraction * hull.length_m;
  const double run_m = hull.length_m / 2.0 - bow_start_m;
  const double u = std::clamp((x_m - bow_start_m) / run_m, 0.0, 1.0);
  return hull.beam_m / 2.0 * std::sqrt(1.0 - u * u);
}

std::vector<Eigen::Vector3d> hull_section(const HullShape& hull, double x_m) {
  const double w = half_beam_m(hull, x_m);
  const double wc = hull.chine_beam_fraction * w;
  return {{x_m, w, hull.height_m},
          {x_m, wc, hull.chine_height_m},
          {x_m, 0.0, 0.0},
          {x_m, -wc, hull.chine_height_m},
          {x_m, -w, hull.height_m}};
}

/// Triangles of the hull in its own frame, unoriented: shell panels between stations, a flat
/// transom and a flat deck.
void hull_triangles(const HullShape& hull, std::vector<Eigen::Vector3d>& points,
                    std::vector<Eigen::Vector3i>& triangles) {
  // Stations as fractions of the half length, closer together where the bow curves.
  const std::vector<double> stations = {-1.0, -0.73, -0.47, -0.2, 0.03,
                                        0.27, 0.47,  0.67,  0.83, 1.0};
  std::vector<std::vector<int>> rings;
  for (const double station : stations) {
    const double x_m = station * hull.length_m / 2.0;
    std::vector<int> ring;
    for (const Eigen::Vector3d& p : hull_section(hull, x_m)) {
      const auto same = std::find(points.begin(), points.end(), p);  // the stem shares points
      ring.push_back(static_cast<int>(same - points.begin()));
      if (same == points.end()) points.push_back(p);
    }
    rings.push_back(ring);
  }
  for (std::size_t s = 0; s + 1 < rings.size(); ++s) {
    for (int k = 0; k + 1 < 5; ++k) {
      const int a = rings[s][k], b = rings[s][k + 1], c = rings[s + 1][k + 1], d = rings[s + 1][k];
      if (k <
          2) {  // port: split along a-c; starboard mirrored (b-d), so no panel folds at the stem
        triangles.emplace_back(a, b, c);
        triangles.emplace_back(a, c, d);
      } else {
        triangles.emplace_back(a, b, d);
        triangles.emplace_back(b, c, d);
      }
    }
  }
  const auto cap = [&](std::vector<int> outline, auto to_2d) {
    const auto project = [&] {
      std::vector<Eigen::Vector2d> polygon;
      for (const int i : outline) polygon.push_back(to_2d(points[i]));
      return polygon;
    };
    if (signed_double_area(project()) < 0.0) {
      std::reverse(outline.begin(), outline.end());
    }
    for (const Eigen::Vector3i& t : triangulate_polygon(project())) {
      triangles.emplace_back(outline[t[0]], outline[t[1]], outline[t[2]]);
    }
  };
  cap(rings.front(), [](const Eigen::Vector3d& p) { return Eigen::Vector2d(p.y(), p.z()); });
  std::vector<int> deck;
  for (const auto& ring : rings) deck.push_back(ring[4]);
  for (auto ring = rings.rbegin() + 1; ring != rings.rend(); ++ring) deck.push_back((*ring)[0]);
  cap(deck, [](const Eigen::Vector3d& p) { return Eigen::Vector2d(p.x(), p.y()); });
}

void add_hull(MeshBuilder& builder, const HullShape& hull, const HullPlacement& placement,
              std::uint32_t group) {
  std::vector<Eigen::Vector3d> points;
  std::vector<Eigen::Vector3i> triangles;
  hull_triangles(hull, points, triangles);
  const Eigen::Matrix3d R_world_hull =
      (Eigen::AngleAxisd(placement.yaw_deg * M_PI / 180.0, Eigen::Vector3d::UnitZ()) *
       Eigen::AngleAxisd(placement.list_deg * M_PI / 180.0, Eigen::Vector3d::UnitX()))
          .toRotationMatrix();
  double z_lowest_m = 0.0;
  for (const Eigen::Vector3d& p : points) z_lowest_m = std::min(z_lowest_m, (R_world_hull * p).z());
  const Eigen::Vector3d t_world_hull(placement.xy_m.x(), placement.xy_m.y(),
                                     placement.bottom_z_m - placement.buried_m - z_lowest_m);
  const int first = static_cast<int>(builder.mesh().vertices_m.size());
  for (const Eigen::Vector3d& p : points) builder.vertex(R_world_hull * p + t_world_hull);
  for (const Eigen::Vector3i& t : triangles) {
    const Eigen::Vector3d a = points[t[0]], b = points[t[1]], c = points[t[2]];
    const Eigen::Vector3d centroid = (a + b + c) / 3.0;
    const double x_axis_m =
        std::clamp(centroid.x(), -hull.length_m / 2.0 + 1.0, hull.length_m / 2.0 - 1.0);
    const Eigen::Vector3d outward = centroid - Eigen::Vector3d(x_axis_m, 0.0, hull.height_m / 2.0);
    const bool flip = (b - a).cross(c - a).dot(outward) < 0.0;
    builder.triangle(first + t[0], first + (flip ? t[2] : t[1]), first + (flip ? t[1] : t[2]),
                     group);
  }
}

}  // namespace msislab::sim
