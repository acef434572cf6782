// A triangle mesh with per-triangle materials: what the simulator's scene is built from. Plain
// data; io/ loads it from OBJ/PLY and checks it (finite vertices, indices in range, >= 1 triangle).
#pragma once

#include <Eigen/Core>
#include <cstdint>
#include <string>
#include <vector>

namespace msislab::sim {

/// How a surface returns sound (docs/simulator.md).
struct Material {
  std::string name;
  float backscatter = 0.5f;  ///< diffuse backscatter strength toward the source, 0..1
  float specular = 0.3f;     ///< fraction of energy reflected in the mirror direction, 0..1
  /// Backscatter per unit area falls as cos^n(incidence): 2 is Lambert's law (a smooth, matte
  /// surface); lower for rough surfaces (rubble, fouled quays) that return sound at grazing too.
  float incidence_exponent = 2.0f;
};

struct TriangleMesh {
  std::vector<Eigen::Vector3f> vertices_m;  ///< x East, y North, z up (m); surface at z = 0
  std::vector<Eigen::Vector3i> triangles;   ///< vertex indices, counter-clockwise
  std::vector<std::uint32_t> material_ids;  ///< one per triangle, into materials
  std::vector<Material> materials;
  std::vector<std::string> group_names;  ///< one per material: the OBJ group/usemtl name
};

}  // namespace msislab::sim
