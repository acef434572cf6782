// Building scene meshes from plan-view geometry: a basin extruded from its outline (walls only on
// the edges that have one, vertical or sloped, and a flat bottom) and vertical prisms standing on
// the bottom (moored boats, pontoons, pilings). Used by the scene tools (docs/scenes.md).
#pragma once

#include <Eigen/Core>
#include <cstdint>
#include <string>
#include <vector>

#include "sim/mesh.hpp"

namespace msislab::sim {

/// Collects vertices and triangles by group, one material per group.
class MeshBuilder {
 public:
  /// Adds a group (OBJ `g`) with its material; returns its id for triangle().
  std::uint32_t group(const std::string& name, float backscatter, float specular);
  int vertex(const Eigen::Vector3d& p_m);
  /// a, b, c counter-clockwise seen from the side the normal points to.
  void triangle(int a, int b, int c, std::uint32_t group);
  /// a, b, c, d counter-clockwise seen from the front.
  void quad(int a, int b, int c, int d, std::uint32_t group);
  const TriangleMesh& mesh() const { return mesh_; }

 private:
  TriangleMesh mesh_;
};

/// A basin from its outline, seen from above.
struct BasinOutline {
  std::vector<Eigen::Vector2d> ccw_polygon_m;  ///< the wall tops at the water line, no repeat
  std::vector<bool> wall_edge;  ///< per edge i (vertex i to i + 1): a wall stands there
};

struct BasinProfile {
  double z_top_m = 1.0;             ///< wall tops, above the surface
  double z_bottom_m = -3.3;         ///< flat bottom
  double wall_foot_offset_m = 0.0;  ///< a wall's foot lies this far into the water from its top
};

/// The bottom polygon: each vertex moved into the water by wall_foot_offset_m along the mitred
/// inward normal of its adjacent wall edges (a vertex between two open edges stays), the mitre
/// limited to twice the offset; where foot edges would cross (an offset longer than a short edge),
/// the shifts of their vertices are halved until they do not. Counter-clockwise like the outline.
std::vector<Eigen::Vector2d> wall_foot_polygon(const BasinOutline& outline, double offset_m);

/// Walls (group walls_group: a quad from the top edge down to the foot edge, facing the water) on
/// the wall edges and the bottom (group bottom_group, facing up, ear-clipped). Throws
/// std::invalid_argument when the foot polygon is not simple (offset too large for the outline).
void add_basin(MeshBuilder& builder, const BasinOutline& outline, const BasinProfile& profile,
               std::uint32_t walls_group, std::uint32_t bottom_group);

/// A square basin joined on its east side to a long straight channel, its far end open: the scene
/// where scan matching along the channel is degenerate (docs/scenes.md, straight_channel).
struct ChannelBasin {
  double basin_side_m = 60.0;       ///< square basin centred on the origin, m
  double channel_length_m = 160.0;  ///< from the basin's east wall eastwards, m
  double channel_width_m = 16.0;    ///< centred on y = 0, m
};

/// The outline, counter-clockwise from the basin's south-west corner; every edge a wall but the
/// channel's far end. Throws std::invalid_argument unless 0 < width < side and length > 0.
BasinOutline channel_basin_outline(const ChannelBasin& geometry);

/// Open water off the corner of two quay walls: the scene where the scans hold only a few sparse
/// returns (docs/scenes.md, open_area). The corner is the origin; one quay runs east along y = 0,
/// the other north along x = 0; the far sides are open. Pilings stand in a field away from both.
struct OpenArea {
  double extent_x_m = 240.0;  ///< the south quay's length and the bottom's extent east, m
  double extent_y_m = 160.0;  ///< the west quay's length and the bottom's extent north, m
  Eigen::Vector2d field_min_m{30.0, 30.0};    ///< the pilings' field, south-west corner, m
  Eigen::Vector2d field_max_m{200.0, 140.0};  ///< the pilings' field, north-east corner, m
  int pilings = 24;
  double min_spacing_m = 15.0;  ///< between two piling centres, m
  std::uint64_t seed = 7;       ///< the pilings' layout
};

/// The outline, counter-clockwise from the corner: walls on the south and west edges only.
/// Throws std::invalid_argument unless both extents are positive and the field lies inside them.
BasinOutline open_area_outline(const OpenArea& geometry);

/// The piling centres: uniform darts in the field (xoshiro256** from the seed), each kept when
/// no earlier one is closer than min_spacing_m, so the same options give the same layout. Throws
/// std::invalid_argument when the pilings do not fit (100000 darts without filling the count).
std::vector<Eigen::Vector2d> open_area_pilings(const OpenArea& geometry);

/// A regular polygon of `sides` vertices on a circle, counter-clockwise: a piling's footprint.
std::vector<Eigen::Vector2d> circle_footprint(const Eigen::Vector2d& centre_m, double radius_m,
                                              int sides);

/// A closed vertical prism over a convex counter-clockwise footprint from z_low_m to z_top_m,
/// normals outward.
void add_prism(MeshBuilder& builder, const std::vector<Eigen::Vector2d>& ccw_footprint_m,
               double z_low_m, double z_top_m, std::uint32_t group);

}  // namespace msislab::sim
