// msislab_make_harbour_scene: a procedural harbour scene (docs/scenes.md): a rectangular basin with
// vertical walls and a flat bottom, two rows of pier pilings and a sunken hull lying on the bottom
// with a list. Deterministic: the same options give the same bytes.
#include <CLI/CLI.hpp>
#include <Eigen/Core>
#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <iostream>
#include <string>
#include <vector>

#include "io/mesh_io.hpp"
#include "sim/mesh.hpp"
#include "sim/polygon_triangulation.hpp"
#include "sim/scene_builder.hpp"

namespace {

struct Options {
  std::string out_path;
  double basin_x_m = 120.0;  ///< basin length East-West, centred on the origin, m
  double basin_y_m = 80.0;   ///< basin width North-South, m
  double depth_m = 6.0;      ///< water depth (bottom at z = -depth), m
  double wall_top_m = 1.0;   ///< walls and pilings rise this far above the surface, m
  int pilings_per_row = 12;  ///< two rows, from the north wall southwards
  double piling_diameter_m = 0.4;
  double piling_spacing_m = 3.0;  ///< along a row, m
  double pier_x_m = 20.0;         ///< pier centre line (x), m
  double pier_width_m = 4.0;      ///< distance between the two rows, m
  int piling_sides = 16;
  Eigen::Vector2d hull_xy_m{-25.0, -15.0};  ///< hull centre, m
  double hull_yaw_deg = 35.0;               ///< bow direction, counter-clockwise from East
  double hull_list_deg = 12.0;              ///< roll to starboard as it lies on the bottom
  double hull_buried_m = 0.3;               ///< keel below the bottom, m
};

using msislab::sim::MeshBuilder;

/// Four walls facing inward and a flat bottom facing up.
void add_basin(MeshBuilder& builder, const Options& options) {
  const std::uint32_t walls = builder.group("walls", 0.6f, 0.3f);
  const std::uint32_t bottom = builder.group("bottom", 0.3f, 0.2f);
  const double hx = options.basin_x_m / 2.0, hy = options.basin_y_m / 2.0;
  const std::vector<Eigen::Vector2d> corners = {{-hx, -hy}, {hx, -hy}, {hx, hy}, {-hx, hy}};
  std::vector<int> top, low;
  for (const Eigen::Vector2d& c : corners) {
    top.push_back(builder.vertex({c.x(), c.y(), options.wall_top_m}));
    low.push_back(builder.vertex({c.x(), c.y(), -options.depth_m}));
  }
  for (int i = 0; i < 4; ++i) {
    const int j = (i + 1) % 4;
    builder.quad(low[i], top[i], top[j], low[j], walls);  // the inside is left of i -> j
  }
  builder.quad(low[0], low[1], low[2], low[3], bottom);
}

void add_pier_pilings(MeshBuilder& builder, const Options& options) {
  const std::uint32_t pilings = builder.group("pilings", 0.7f, 0.2f);
  const double north_wall_y_m = options.basin_y_m / 2.0;
  for (const double side : {-0.5, 0.5}) {
    for (int k = 0; k < options.pilings_per_row; ++k) {
      const Eigen::Vector2d centre(options.pier_x_m + side * options.pier_width_m,
                                   north_wall_y_m - 2.0 - k * options.piling_spacing_m);
      msislab::sim::add_prism(builder,
                              msislab::sim::circle_footprint(
                                  centre, options.piling_diameter_m / 2.0, options.piling_sides),
                              -options.depth_m, options.wall_top_m, pilings);
    }
  }
}

/// Hull frame: x forward (bow at +7.5 m), y to port, z up from the keel; 15 x 4 x 3 m. Sections
/// of five points (port deck edge, port chine, keel, starboard chine, starboard deck edge) at
/// stations along x; parallel-sided aft, the deck edge curving into a vertical stem at the bow.
struct HullShape {
  double length_m = 15.0;
  double beam_m = 4.0;
  double height_m = 3.0;
  double chine_height_m = 1.2;
  double chine_beam_fraction = 0.85;
  double parallel_fraction = 0.65;  ///< aft part with full beam
};

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
    if (msislab::sim::signed_double_area(project()) < 0.0) {
      std::reverse(outline.begin(), outline.end());
    }
    for (const Eigen::Vector3i& t : msislab::sim::triangulate_polygon(project())) {
      triangles.emplace_back(outline[t[0]], outline[t[1]], outline[t[2]]);
    }
  };
  cap(rings.front(), [](const Eigen::Vector3d& p) { return Eigen::Vector2d(p.y(), p.z()); });
  std::vector<int> deck;
  for (const auto& ring : rings) deck.push_back(ring[4]);
  for (auto ring = rings.rbegin() + 1; ring != rings.rend(); ++ring) deck.push_back((*ring)[0]);
  cap(deck, [](const Eigen::Vector3d& p) { return Eigen::Vector2d(p.x(), p.y()); });
}

/// The hull placed on the bottom (listed, turned, keel buried), its normals turned outward: away
/// from the hull's axis (x clamped inside the hull, y = 0, z at half height).
void add_hull(MeshBuilder& builder, const Options& options) {
  const std::uint32_t group = builder.group("hull", 0.8f, 0.4f);
  const HullShape hull;
  std::vector<Eigen::Vector3d> points;
  std::vector<Eigen::Vector3i> triangles;
  hull_triangles(hull, points, triangles);
  const Eigen::Matrix3d R_world_hull =
      (Eigen::AngleAxisd(options.hull_yaw_deg * M_PI / 180.0, Eigen::Vector3d::UnitZ()) *
       Eigen::AngleAxisd(options.hull_list_deg * M_PI / 180.0, Eigen::Vector3d::UnitX()))
          .toRotationMatrix();
  double z_lowest_m = 0.0;
  for (const Eigen::Vector3d& p : points) z_lowest_m = std::min(z_lowest_m, (R_world_hull * p).z());
  const Eigen::Vector3d t_world_hull(options.hull_xy_m.x(), options.hull_xy_m.y(),
                                     -options.depth_m - options.hull_buried_m - z_lowest_m);
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

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"Write the procedural harbour scene: basin, pier pilings, sunken hull (OBJ)"};
  Options options;
  app.add_option("--out", options.out_path, "Output OBJ")->required();
  app.add_option("--depth", options.depth_m, "Water depth, m")
      ->check(CLI::Range(4.0, 50.0))
      ->capture_default_str();
  CLI11_PARSE(app, argc, argv);

  MeshBuilder builder;
  add_basin(builder, options);
  add_pier_pilings(builder, options);
  add_hull(builder, options);
  const msislab::sim::TriangleMesh& mesh = builder.mesh();
  try {
    msislab::io::write_obj(options.out_path, mesh);
  } catch (const std::exception& e) {
    std::cerr << "msislab_make_harbour_scene: " << e.what() << "\n";
    return 2;
  }
  std::vector<int> per_group(mesh.group_names.size(), 0);
  for (const std::uint32_t id : mesh.material_ids) ++per_group[id];
  std::cout << "harbour: " << mesh.vertices_m.size() << " vertices, " << mesh.triangles.size()
            << " triangles (";
  for (std::size_t g = 0; g < per_group.size(); ++g) {
    std::cout << (g ? ", " : "") << mesh.group_names[g] << " " << per_group[g];
  }
  std::cout << ")\nwrote " << options.out_path << "\n";
  return 0;
}
