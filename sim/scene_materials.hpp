// Default materials by geometry. A mesh written by hand often has one group, or groups named
// otherwise than `walls` and `bottom`, so the sea floor is recognised by its shape: the faces that
// are near-horizontal with nothing of the mesh under them. They take a darker default than the
// rest (docs/scenes.md gives the backscatter strengths and why).
#pragma once

#include <set>
#include <string>
#include <vector>

#include "sim/mesh.hpp"

namespace msislab::sim {

/// A face is near-horizontal when its normal lies within this angle of the vertical (either way
/// up: hand-written meshes are not always wound consistently).
inline constexpr double kMaxBottomTilt_deg = 30.0;

/// Per triangle: true for the sea floor, a near-horizontal face with no other face of the mesh
/// under its centre. A sunken deck, a pier deck or a box top has the floor under it; a sloping
/// floor is still floor. Degenerate (zero-area) faces are not.
std::vector<bool> bottom_faces(const TriangleMesh& mesh);

/// Gives the floor faces (`is_bottom`) of every group not in `explicit_groups` the material
/// `bottom`, named after the group, or "GROUP/bottom" ("bottom" for the unnamed group) when the
/// group also has faces that are not floor. The other faces keep their materials.
void assign_bottom_material(TriangleMesh& mesh, const std::vector<bool>& is_bottom,
                            const std::set<std::string>& explicit_groups, const Material& bottom);

/// Area-weighted mean backscatter of the floor and of the steep faces (walls, pilings, hull
/// sides: normal within 30 deg of the horizontal), with their areas.
struct SurfaceBrightness {
  double bottom_backscatter = 0.0;
  double bottom_area_m2 = 0.0;
  double walls_backscatter = 0.0;
  double walls_area_m2 = 0.0;
};
SurfaceBrightness surface_brightness(const TriangleMesh& mesh, const std::vector<bool>& is_bottom);

/// A floor backscattering less than this many dB below the walls outshines them in the beam's
/// lower half (docs/scenes.md: the floor is seen over a far larger area than a wall).
inline constexpr double kMinBottomContrast_dB = 10.0;

/// The floor returns about as much as the walls: less than kMinBottomContrast_dB darker. False
/// when the mesh has no floor or no walls.
bool bottom_as_bright_as_walls(const SurfaceBrightness& brightness);

}  // namespace msislab::sim
