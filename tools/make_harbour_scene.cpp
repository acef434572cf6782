// msislab_make_harbour_scene: a procedural harbour scene (docs/scenes.md): a rectangular basin with
// vertical walls and a flat bottom, two rows of pier pilings and a sunken hull lying on the bottom
// with a list. Deterministic: the same options give the same bytes.
#include <CLI/CLI.hpp>
#include <Eigen/Core>
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <iostream>
#include <string>
#include <vector>

#include "io/mesh_io.hpp"
#include "sim/hull.hpp"
#include "sim/mesh.hpp"
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

/// The sunken hull (sim/hull) on the bottom: listed, turned, keel buried.
void add_hull(MeshBuilder& builder, const Options& options) {
  const std::uint32_t group = builder.group("hull", 0.8f, 0.4f);
  msislab::sim::HullPlacement placement;
  placement.xy_m = options.hull_xy_m;
  placement.yaw_deg = options.hull_yaw_deg;
  placement.list_deg = options.hull_list_deg;
  placement.buried_m = options.hull_buried_m;
  placement.bottom_z_m = -options.depth_m;
  msislab::sim::add_hull(builder, msislab::sim::HullShape{}, placement, group);
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
