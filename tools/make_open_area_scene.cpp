// msislab_make_open_area_scene: open water off the corner of two quays, with a sparse field of
// pilings (docs/scenes.md): the geometry where a scan holds only a few returns. Deterministic: the
// same options give the same bytes.
#include <CLI/CLI.hpp>
#include <exception>
#include <iostream>
#include <string>

#include "io/mesh_io.hpp"
#include "sim/scene_builder.hpp"

int main(int argc, char** argv) {
  CLI::App app{"Write the open-area scene: two quays and a sparse field of pilings (OBJ)"};
  std::string out_path;
  msislab::sim::OpenArea geometry;
  msislab::sim::BasinProfile profile;
  profile.z_bottom_m = -3.4;       // the St. Pere replica's bottom: 1.9 m under a vehicle at 1.5 m
  double piling_diameter_m = 2.0;  // mooring dolphins: clusters of piles, one strong target
  int piling_sides = 12;
  app.add_option("--out", out_path, "Output OBJ")->required();
  app.add_option("--pilings", geometry.pilings, "Number of pilings")
      ->check(CLI::NonNegativeNumber)
      ->capture_default_str();
  app.add_option("--spacing", geometry.min_spacing_m, "Minimum distance between pilings, m")
      ->check(CLI::NonNegativeNumber)
      ->capture_default_str();
  app.add_option("--piling-diameter", piling_diameter_m, "Piling diameter, m")
      ->check(CLI::PositiveNumber)
      ->capture_default_str();
  app.add_option("--seed", geometry.seed, "Seed of the pilings' layout")->capture_default_str();
  CLI11_PARSE(app, argc, argv);
  try {
    msislab::sim::MeshBuilder builder;
    const auto walls = builder.group("walls", 0.5f, 0.05f);
    const auto bottom = builder.group("bottom", 0.003f, 0.3f);
    const auto pilings = builder.group("pilings", 0.7f, 0.2f);
    msislab::sim::add_basin(builder, msislab::sim::open_area_outline(geometry), profile, walls,
                            bottom);
    for (const Eigen::Vector2d& centre_m : msislab::sim::open_area_pilings(geometry)) {
      msislab::sim::add_prism(
          builder, msislab::sim::circle_footprint(centre_m, piling_diameter_m / 2.0, piling_sides),
          profile.z_bottom_m, profile.z_top_m, pilings);
    }
    msislab::io::write_obj(out_path, builder.mesh());
    std::cout << "open area: " << builder.mesh().vertices_m.size() << " vertices, "
              << builder.mesh().triangles.size() << " triangles\nwrote " << out_path << "\n";
  } catch (const std::exception& e) {
    std::cerr << "msislab_make_open_area_scene: " << e.what() << "\n";
    return 2;
  }
  return 0;
}
