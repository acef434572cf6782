#include "io/mesh_io.hpp"

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <charconv>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <limits>
#include <string_view>
#include <system_error>
#include <vector>

#include "io/atomic_file.hpp"
#include "io/input_error.hpp"
#include "io/ply.hpp"
#include "io/text_lines.hpp"

namespace msislab::io {
namespace {

// The material of a group: by_group's entry if any, else the default one named after the group.
sim::Material material_for(const MeshMaterials& materials, const std::string& group) {
  const auto found = materials.by_group.find(group);
  sim::Material material =
      found != materials.by_group.end() ? found->second : materials.default_material;
  if (found == materials.by_group.end() || material.name.empty()) material.name = group;
  return material;
}

// Reads an OBJ line by line; faces take the material of the current g/o/usemtl name.
class ObjReader {
 public:
  ObjReader(const std::string& path, const MeshMaterials& materials)
      : lines_(path, '#'), materials_(materials) {}

  sim::TriangleMesh read() {
    while (lines_.next()) read_line();
    if (mesh_.triangles.empty()) fail_file(lines_.path(), "no triangles");
    return std::move(mesh_);
  }

 private:
  void read_line() {
    // A '#' field starts a trailing comment.
    std::size_t used = 1;
    while (used < lines_.size() && lines_.field(used).front() != '#') ++used;
    const std::string_view keyword = lines_.field(0);
    if (keyword == "v") {
      read_vertex(used);
    } else if (keyword == "f") {
      read_face(used);
    } else if (keyword == "g" || keyword == "o" || keyword == "usemtl") {
      group_ = joined_name(used);
    } else if (keyword != "vn" && keyword != "vt" && keyword != "s" && keyword != "mtllib") {
      lines_.fail("unsupported OBJ statement '" + std::string(keyword) + "'");
    }
  }

  // `v x y z`; a fourth w or colour values may follow and are ignored.
  void read_vertex(std::size_t used) {
    if (used < 4)
      lines_.fail("vertex has " + std::to_string(used - 1) + " coordinates; expected 3");
    Eigen::Vector3f vertex_m;
    constexpr const char* kAxes[] = {"x", "y", "z"};
    for (int axis = 0; axis < 3; ++axis) {
      const double value = lines_.number(static_cast<std::size_t>(axis) + 1, kAxes[axis]);
      if (std::abs(value) > std::numeric_limits<float>::max())
        lines_.fail(std::string("coordinate ") + kAxes[axis] + " = " + format_number(value) +
                    " is out of float range");
      vertex_m[axis] = static_cast<float>(value);
    }
    mesh_.vertices_m.push_back(vertex_m);
  }

  void read_face(std::size_t used) {
    if (used != 4)
      lines_.fail("face has " + std::to_string(used - 1) +
                  " vertices; only triangles are supported");
    Eigen::Vector3i triangle;
    for (int corner = 0; corner < 3; ++corner)
      triangle[corner] = vertex_index(static_cast<std::size_t>(corner) + 1);
    mesh_.triangles.push_back(triangle);
    mesh_.material_ids.push_back(group_id());
  }

  // One face vertex, `a`, `a/b`, `a/b/c` or `a//c`: the 0-based index of a; negative a counts back
  // from the last vertex read. Faces may only use vertices defined above them.
  int vertex_index(std::size_t field) const {
    const std::string_view token = lines_.field(field);
    const FieldAt at{lines_.path(), lines_.line_number(), field + 1, "vertex index"};
    const std::int64_t index = first_of_slashed(token, at);
    const auto count = static_cast<std::int64_t>(mesh_.vertices_m.size());
    if (index == 0) fail_field(at, token, "is invalid: OBJ vertex indices start at 1");
    const std::int64_t zero_based = index > 0 ? index - 1 : count + index;
    if (zero_based < 0 || zero_based >= count)
      fail_field(at, token,
                 "is out of range (" + std::to_string(count) + " vertices defined so far)");
    return static_cast<int>(zero_based);
  }

  // Checks the syntax of all parts (texture and normal indices may be empty) and returns the first.
  static std::int64_t first_of_slashed(std::string_view token, const FieldAt& at) {
    std::int64_t first = 0;
    std::size_t start = 0;
    for (int part = 0; part < 3; ++part) {
      const std::size_t end = std::min(token.find('/', start), token.size());
      std::int64_t value = 0;
      const auto parsed = std::from_chars(token.data() + start, token.data() + end, value);
      const bool empty_allowed = part > 0 && end == start;
      if (!empty_allowed && (parsed.ec != std::errc() || parsed.ptr != token.data() + end)) break;
      if (part == 0) first = value;
      if (end == token.size()) return first;
      start = end + 1;
    }
    fail_field(at, token, "is not a face vertex (a, a/b, a/b/c or a//c with integers)");
  }

  std::string joined_name(std::size_t used) const {
    std::string name;
    for (std::size_t i = 1; i < used; ++i) {
      if (i > 1) name += ' ';
      name += lines_.field(i);
    }
    return name;
  }

  // Materials are created when a group's first face is read, so groups without faces get none.
  std::uint32_t group_id() {
    const auto found = group_ids_.find(group_);
    if (found != group_ids_.end()) return found->second;
    const auto id = static_cast<std::uint32_t>(mesh_.materials.size());
    group_ids_.emplace(group_, id);
    mesh_.materials.push_back(material_for(materials_, group_));
    mesh_.group_names.push_back(group_);
    return id;
  }

  DataLines lines_;
  const MeshMaterials& materials_;
  sim::TriangleMesh mesh_;
  std::map<std::string, std::uint32_t> group_ids_;
  std::string group_;  ///< "" until the first g/o/usemtl line
};

// PLY has no groups: one material, the default (or by_group[""]), for every triangle.
sim::TriangleMesh read_ply_mesh(const std::string& path, const MeshMaterials& materials) {
  std::error_code error;
  if (std::filesystem::exists(path, error) && std::filesystem::is_regular_file(path, error) &&
      std::filesystem::file_size(path, error) == 0)
    fail_file(path, "no triangles (empty file)");
  const PlyData ply = read_ply(path);
  sim::TriangleMesh mesh;
  for (std::size_t i = 0; i < ply.vertices_m.size(); ++i) {
    if ((ply.vertices_m[i].array().abs() > std::numeric_limits<float>::max()).any())
      fail_file(path, "vertex " + std::to_string(i) + " has a non-finite coordinate");
    mesh.vertices_m.push_back(ply.vertices_m[i].cast<float>());
  }
  const auto vertex_count = static_cast<std::int64_t>(mesh.vertices_m.size());
  for (std::size_t f = 0; f < ply.faces.size(); ++f) {
    const std::vector<std::int64_t>& corners = ply.faces[f];
    const std::string face = "face " + std::to_string(f);
    if (corners.size() != 3)
      fail_file(path, face + " has " + std::to_string(corners.size()) +
                          " vertices; only triangles are supported");
    for (const std::int64_t corner : corners)
      if (corner < 0 || corner >= vertex_count)
        fail_file(path, face + " has a vertex index out of range");
    mesh.triangles.emplace_back(static_cast<int>(corners[0]), static_cast<int>(corners[1]),
                                static_cast<int>(corners[2]));
  }
  if (mesh.triangles.empty()) fail_file(path, "no triangles");
  mesh.material_ids.assign(mesh.triangles.size(), 0);
  mesh.materials.push_back(material_for(materials, ""));
  mesh.group_names.emplace_back();
  return mesh;
}

std::string lowercase_extension(const std::string& path) {
  std::string extension = std::filesystem::path(path).extension().string();
  for (char& c : extension) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return extension;
}

// The shortest float text, unless reading it as double and rounding to float (what read_mesh does)
// would land on a neighbour; then the float's exact double value.
void append_float(std::string& out, float value) {
  char buffer[32];
  const auto result = std::to_chars(buffer, buffer + sizeof(buffer), value);
  double read_back = 0.0;
  std::from_chars(buffer, result.ptr, read_back);
  if (static_cast<float>(read_back) == value) {
    out.append(buffer, result.ptr);
  } else {
    append_number(out, static_cast<double>(value));
  }
}

void append_obj_groups(const std::string& path, const sim::TriangleMesh& mesh, std::string& text) {
  if (mesh.material_ids.size() != mesh.triangles.size())
    fail_file(path, "cannot write: material_ids and triangles differ in size");
  std::vector<std::vector<std::size_t>> faces_by_material(mesh.materials.size());
  for (std::size_t i = 0; i < mesh.triangles.size(); ++i) {
    if (mesh.material_ids[i] >= mesh.materials.size())
      fail_file(path, "cannot write: triangle " + std::to_string(i) + " has no material");
    faces_by_material[mesh.material_ids[i]].push_back(i);
  }
  for (std::size_t m = 0; m < mesh.materials.size(); ++m) {
    const std::string& name =
        m < mesh.group_names.size() ? mesh.group_names[m] : mesh.materials[m].name;
    text += name.empty() ? "g\n" : "g " + name + "\n";
    for (const std::size_t i : faces_by_material[m]) {
      const Eigen::Vector3i& triangle = mesh.triangles[i];
      text += "f " + std::to_string(triangle[0] + 1) + ' ' + std::to_string(triangle[1] + 1) + ' ' +
              std::to_string(triangle[2] + 1) + '\n';
    }
  }
}

}  // namespace

sim::TriangleMesh read_mesh(const std::string& path, const MeshMaterials& materials) {
  const std::string extension = lowercase_extension(path);
  if (extension == ".obj") return ObjReader(path, materials).read();
  if (extension == ".ply") return read_ply_mesh(path, materials);
  fail_file(path, "unknown mesh format '" + extension + "' (expected .obj or .ply)");
}

// Triangles are written grouped by material, in their original order within each group, so a
// mesh whose triangles interleave materials reads back reordered (same set, same groups). A group
// without triangles reads back as no material at all.
void write_obj(const std::string& path, const sim::TriangleMesh& mesh) {
  std::string text = "# msislab scene\n";
  for (std::size_t i = 0; i < mesh.vertices_m.size(); ++i) {
    text += 'v';
    for (int axis = 0; axis < 3; ++axis) {
      check_finite(mesh.vertices_m[i][axis], path, i + 1, "vertex coordinate");
      text += ' ';
      append_float(text, mesh.vertices_m[i][axis]);
    }
    text += '\n';
  }
  append_obj_groups(path, mesh, text);
  write_text_atomically(path, text);
}

}  // namespace msislab::io
