// Scene meshes: OBJ (own strict reader: v, f, g, o, usemtl; faces must be triangles) and PLY
// (io/ply, ASCII or binary, triangles only), and an OBJ writer for the scene tools.
// Errors name the file and line (OBJ) or the file (PLY): missing, empty (no triangle), a face that
// is not a triangle, an index out of range, a non-finite coordinate.
#pragma once

#include <map>
#include <string>

#include "sim/mesh.hpp"

namespace msislab::io {

/// Which material each part of a mesh gets. OBJ groups (`g`, `o` or `usemtl` names) found in
/// `by_group` get that material; everything else gets `default_material`.
struct MeshMaterials {
  sim::Material default_material;
  std::map<std::string, sim::Material> by_group;
};

/// Loads .obj or .ply (by extension; anything else is an error).
sim::TriangleMesh read_mesh(const std::string& path, const MeshMaterials& materials);

/// Writes an OBJ with one `g NAME` block per material group (group_names), atomically.
void write_obj(const std::string& path, const sim::TriangleMesh& mesh);

}  // namespace msislab::io
