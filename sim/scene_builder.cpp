#include "sim/scene_builder.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

#include "sim/polygon_triangulation.hpp"
#include "sim/random.hpp"

namespace msislab::sim {

std::uint32_t MeshBuilder::group(const std::string& name, float backscatter, float specular) {
  mesh_.materials.push_back({name, backscatter, specular});
  mesh_.group_names.push_back(name);
  return static_cast<std::uint32_t>(mesh_.materials.size() - 1);
}

int MeshBuilder::vertex(const Eigen::Vector3d& p_m) {
  mesh_.vertices_m.push_back(p_m.cast<float>());
  return static_cast<int>(mesh_.vertices_m.size() - 1);
}

void MeshBuilder::triangle(int a, int b, int c, std::uint32_t group) {
  mesh_.triangles.emplace_back(a, b, c);
  mesh_.material_ids.push_back(group);
}

void MeshBuilder::quad(int a, int b, int c, int d, std::uint32_t group) {
  triangle(a, b, c, group);
  triangle(a, c, d, group);
}

namespace {

/// The unit normal to the left of a -> b: into the water of a counter-clockwise outline.
Eigen::Vector2d inward_normal(const Eigen::Vector2d& a, const Eigen::Vector2d& b) {
  const Eigen::Vector2d d = (b - a).normalized();
  return {-d.y(), d.x()};
}

}  // namespace

std::vector<Eigen::Vector2d> wall_foot_polygon(const BasinOutline& outline, double offset_m) {
  const std::vector<Eigen::Vector2d>& p = outline.ccw_polygon_m;
  const std::size_t n = p.size();
  std::vector<Eigen::Vector2d> shift(n, Eigen::Vector2d::Zero());
  for (std::size_t i = 0; i < n && offset_m != 0.0; ++i) {
    const std::size_t before = (i + n - 1) % n, after = (i + 1) % n;
    const bool wall_before = outline.wall_edge[before], wall_after = outline.wall_edge[i];
    if (!wall_before && !wall_after) continue;
    const Eigen::Vector2d n_before = inward_normal(p[before], p[i]);
    const Eigen::Vector2d n_after = inward_normal(p[i], p[after]);
    if (wall_before != wall_after) {
      shift[i] = offset_m * (wall_before ? n_before : n_after);
      continue;
    }
    // Mitre: the point offset_m from both edges, length offset_m / cos(half the turn).
    const Eigen::Vector2d bisector = (n_before + n_after).normalized();
    shift[i] = bisector * offset_m / std::max(bisector.dot(n_before), 0.5);
  }
  // Where two foot edges cross (a shift longer than a short edge), the shifts of their four
  // vertices are halved until none does: the foot comes closer to the top there.
  std::vector<Eigen::Vector2d> foot(n);
  for (int halving = 0; halving <= 30; ++halving) {
    for (std::size_t i = 0; i < n; ++i) foot[i] = p[i] + shift[i];
    const auto crossing = find_crossing_edges(foot);
    if (!crossing) break;
    for (const int e : {crossing->first, crossing->second}) {
      shift[static_cast<std::size_t>(e)] *= 0.5;
      shift[(static_cast<std::size_t>(e) + 1) % n] *= 0.5;
    }
  }
  return foot;
}

void add_basin(MeshBuilder& builder, const BasinOutline& outline, const BasinProfile& profile,
               std::uint32_t walls_group, std::uint32_t bottom_group) {
  const std::size_t n = outline.ccw_polygon_m.size();
  if (n < 3 || outline.wall_edge.size() != n) {
    throw std::invalid_argument("add_basin: needs >= 3 vertices and one wall flag per edge");
  }
  const std::vector<Eigen::Vector2d> foot = wall_foot_polygon(outline, profile.wall_foot_offset_m);
  if (find_crossing_edges(foot)) {
    throw std::invalid_argument("add_basin: the wall foot polygon crosses itself");
  }
  std::vector<int> foot_index, top_index(n, -1);
  for (const Eigen::Vector2d& q : foot) {
    foot_index.push_back(builder.vertex({q.x(), q.y(), profile.z_bottom_m}));
  }
  const auto top = [&](std::size_t i) {
    if (top_index[i] < 0) {
      const Eigen::Vector2d& q = outline.ccw_polygon_m[i];
      top_index[i] = builder.vertex({q.x(), q.y(), profile.z_top_m});
    }
    return top_index[i];
  };
  for (std::size_t i = 0; i < n; ++i) {
    if (!outline.wall_edge[i]) continue;
    const std::size_t j = (i + 1) % n;
    // Counter-clockwise seen from the outline's inside (its left): the normals face the water.
    builder.triangle(foot_index[i], top(j), foot_index[j], walls_group);
    builder.triangle(foot_index[i], top(i), top(j), walls_group);
  }
  for (const Eigen::Vector3i& t : triangulate_polygon(foot)) {
    builder.triangle(foot_index[t[0]], foot_index[t[1]], foot_index[t[2]], bottom_group);
  }
}

void add_prism(MeshBuilder& builder, const std::vector<Eigen::Vector2d>& ccw_footprint_m,
               double z_low_m, double z_top_m, std::uint32_t group) {
  std::vector<int> low, high;
  for (const Eigen::Vector2d& q : ccw_footprint_m) {
    low.push_back(builder.vertex({q.x(), q.y(), z_low_m}));
    high.push_back(builder.vertex({q.x(), q.y(), z_top_m}));
  }
  const int n = static_cast<int>(ccw_footprint_m.size());
  for (int k = 0; k < n; ++k) {
    const int next = (k + 1) % n;
    builder.quad(low[k], low[next], high[next], high[k], group);  // the outside is right of k
  }
  for (int k = 1; k + 1 < n; ++k) {
    builder.triangle(high[0], high[k], high[k + 1], group);
    builder.triangle(low[0], low[k + 1], low[k], group);
  }
}

BasinOutline channel_basin_outline(const ChannelBasin& geometry) {
  const double h = geometry.basin_side_m / 2.0, w = geometry.channel_width_m / 2.0;
  if (!(geometry.channel_width_m > 0.0 && geometry.channel_width_m < geometry.basin_side_m &&
        geometry.channel_length_m > 0.0)) {
    throw std::invalid_argument(
        "channel basin: needs 0 < channel width < basin side and a positive channel length");
  }
  const double x_end = h + geometry.channel_length_m;
  BasinOutline outline;
  outline.ccw_polygon_m = {{-h, -h},   {h, -h}, {h, -w}, {x_end, -w},
                           {x_end, w}, {h, w},  {h, h},  {-h, h}};
  outline.wall_edge = {true, true, true, false, true, true, true, true};  // edge 3: the far end
  return outline;
}

BasinOutline open_area_outline(const OpenArea& geometry) {
  const Eigen::Vector2d extent_m(geometry.extent_x_m, geometry.extent_y_m);
  if (!(extent_m.minCoeff() > 0.0 && (geometry.field_min_m.array() >= 0.0).all() &&
        (geometry.field_min_m.array() < geometry.field_max_m.array()).all() &&
        (geometry.field_max_m.array() <= extent_m.array()).all())) {
    throw std::invalid_argument(
        "open area: needs positive extents and a pilings' field inside them");
  }
  BasinOutline outline;
  outline.ccw_polygon_m = {{0.0, 0.0}, {extent_m.x(), 0.0}, extent_m, {0.0, extent_m.y()}};
  outline.wall_edge = {true, false, false, true};  // the south and west quays
  return outline;
}

std::vector<Eigen::Vector2d> open_area_pilings(const OpenArea& geometry) {
  Rng rng(geometry.seed);
  const Eigen::Vector2d size_m = geometry.field_max_m - geometry.field_min_m;
  std::vector<Eigen::Vector2d> centres_m;
  for (int dart = 0; dart < 100000 && static_cast<int>(centres_m.size()) < geometry.pilings;
       ++dart) {
    const Eigen::Vector2d c_m = geometry.field_min_m + draw_y_then_x([&] {
                                                         return unit_interval(rng());
                                                       }).cwiseProduct(size_m);
    const bool clear = std::none_of(centres_m.begin(), centres_m.end(), [&](const auto& other) {
      return (other - c_m).norm() < geometry.min_spacing_m;
    });
    if (clear) centres_m.push_back(c_m);
  }
  if (static_cast<int>(centres_m.size()) < geometry.pilings) {
    throw std::invalid_argument("open area: " + std::to_string(geometry.pilings) +
                                " pilings do not fit in the field at the minimum spacing");
  }
  return centres_m;
}

std::vector<Eigen::Vector2d> circle_footprint(const Eigen::Vector2d& centre_m, double radius_m,
                                              int sides) {
  std::vector<Eigen::Vector2d> footprint_m;
  for (int k = 0; k < sides; ++k) {
    const double angle_rad = 2.0 * M_PI * k / sides;
    footprint_m.push_back(centre_m +
                          radius_m * Eigen::Vector2d(std::cos(angle_rad), std::sin(angle_rad)));
  }
  return footprint_m;
}

}  // namespace msislab::sim
