// A sunken hull for the procedural harbour scene (tools/make_harbour_scene): a closed mesh of a
// small workboat (shell panels between stations, a flat transom and deck) placed on the bottom,
// listed, turned and partly buried, with every normal pointing out.
#pragma once

#include <Eigen/Core>
#include <cstdint>
#include <vector>

#include "sim/scene_builder.hpp"

namespace msislab::sim {

/// Hull frame: x forward (bow at +length/2), y to port, z up from the keel. Sections of five
/// points (port deck edge, port chine, keel, starboard chine, starboard deck edge) at stations
/// along x; parallel-sided aft, the deck edge curving into a vertical stem at the bow.
struct HullShape {
  double length_m = 15.0;
  double beam_m = 4.0;
  double height_m = 3.0;
  double chine_height_m = 1.2;
  double chine_beam_fraction = 0.85;
  double parallel_fraction = 0.65;  ///< aft part with full beam
};

/// Where the hull lies: centre, bow direction (counter-clockwise from East), list (roll to
/// starboard), how deep the keel is buried below the bottom at z = bottom_z_m.
struct HullPlacement {
  Eigen::Vector2d xy_m{0.0, 0.0};
  double yaw_deg = 0.0;
  double list_deg = 0.0;
  double buried_m = 0.0;
  double bottom_z_m = 0.0;
};

/// Half the beam at x (full aft, an ellipse towards the stem).
double half_beam_m(const HullShape& hull, double x_m);
/// The five section points at x.
std::vector<Eigen::Vector3d> hull_section(const HullShape& hull, double x_m);
/// The hull's triangles in its own frame, unoriented; the stem's points are shared.
void hull_triangles(const HullShape& hull, std::vector<Eigen::Vector3d>& points,
                    std::vector<Eigen::Vector3i>& triangles);
/// Adds the hull, placed, to `builder` in `group`, its normals turned outward: away from the
/// hull's axis (x clamped inside the hull, y = 0, z at half height).
void add_hull(MeshBuilder& builder, const HullShape& hull, const HullPlacement& placement,
              std::uint32_t group);

}  // namespace msislab::sim
