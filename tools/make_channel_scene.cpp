// msislab_make_channel_scene: a square basin joined to a long straight channel with smooth walls
// and an open far end (docs/scenes.md): the geometry where scan matching along the channel's axis
// is degenerate. Deterministic: the same options give the same bytes.
#include <CLI/CLI.hpp>
#include <exception>
#include <iostream>
#include <string>

#include "io/mesh_io.hpp"
#include "sim/scene_builder.hpp"

int main(int argc, char** argv) {
  CLI::App app{"Write the straight-channel scene: a square basin and a long channel (OBJ)"};
  std::string out_path;
  msislab::sim::ChannelBasin geometry;
  msislab::sim::BasinProfile profile;
  profile.z_bottom_m = -3.4;  // the St. Pere replica's bottom: 1.9 m under a vehicle at 1.5 m
  app.add_option("--out", out_path, "Output OBJ")->required();
  app.add_option("--basin-side", geometry.basin_side_m, "Side of the square basin, m")
      ->check(CLI::PositiveNumber)
      ->capture_default_str();
  app.add_option("--channel-length", geometry.channel_length_m, "Channel length, m")
      ->check(CLI::PositiveNumber)
      ->capture_default_str();
  app.add_option("--channel-width", geometry.channel_width_m, "Channel width, m")
      ->check(CLI::PositiveNumber)
      ->capture_default_str();
  CLI11_PARSE(app, argc, argv);
  try {
    msislab::sim::MeshBuilder builder;
    const auto walls = builder.group("walls", 0.5f, 0.05f);
    const auto bottom = builder.group("bottom", 0.003f, 0.3f);
    msislab::sim::add_basin(builder, msislab::sim::channel_basin_outline(geometry), profile, walls,
                            bottom);
    msislab::io::write_obj(out_path, builder.mesh());
    std::cout << "channel: " << builder.mesh().vertices_m.size() << " vertices, "
              << builder.mesh().triangles.size() << " triangles\nwrote " << out_path << "\n";
  } catch (const std::exception& e) {
    std::cerr << "msislab_make_channel_scene: " << e.what() << "\n";
    return 2;
  }
  return 0;
}
