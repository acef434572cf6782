// Mesh loading: OBJ (groups, usemtl, comments, negative and a/b/c indices), PLY ASCII and binary,
// the OBJ round trip, and the one-line errors for bad meshes (file and, for OBJ, line).
#include "io/mesh_io.hpp"

#include <gtest/gtest.h>

#include <cstdint>
#include <cstdio>
#include <cstring>
#include <functional>
#include <string>

#include "io/input_error.hpp"
#include "test_support.hpp"

namespace msislab::io {
namespace {

using msislab::testing::read_text;
using msislab::testing::TempDir;
using msislab::testing::write_text;

MeshMaterials concrete_walls() {
  MeshMaterials materials;
  materials.default_material = {"default", 0.5f, 0.3f};
  materials.by_group["walls"] = {"concrete", 0.9f, 0.1f};
  return materials;
}

// The message of the InputError that `load` throws.
std::string error_of(const std::function<void()>& load) {
  try {
    load();
  } catch (const InputError& error) {
    return error.what();
  }
  ADD_FAILURE() << "no InputError thrown";
  return "";
}

std::string mesh_error(const TempDir& dir, const std::string& name, const std::string& text) {
  const std::string path = write_text(dir.file(name), text);
  return error_of([&] { read_mesh(path, MeshMaterials{}); });
}

constexpr const char* kObj = R"(# a test mesh
mtllib scene.mtl
v 0 0 0
v 1 0 0
v 1 1 0
v 0 1 -2.5 1.0   # a w coordinate and a trailing comment
vt 0 0
vn 0 0 1

f 1 2 3
g walls
s 1
f 1/1/1 2/1/1 4/1/1
f -4//1 -2//1 -1//1
o buoy
v 5 5 5 0.5 0.5 0.5
f 1/1 3/1 -1/1
usemtl walls
f 2 3 5
)";

TEST(MeshIo, ObjGroupsIndicesAndMaterials) {
  TempDir dir;
  const sim::TriangleMesh mesh = read_mesh(write_text(dir.file("a.obj"), kObj), concrete_walls());
  ASSERT_EQ(mesh.vertices_m.size(), 5u);
  EXPECT_EQ(mesh.vertices_m[3], Eigen::Vector3f(0, 1, -2.5f));
  EXPECT_EQ(mesh.vertices_m[4], Eigen::Vector3f(5, 5, 5));
  const std::vector<Eigen::Vector3i> triangles = {
      {0, 1, 2}, {0, 1, 3}, {0, 2, 3}, {0, 2, 4}, {1, 2, 4}};
  EXPECT_EQ(mesh.triangles, triangles);
  EXPECT_EQ(mesh.material_ids, (std::vector<std::uint32_t>{0, 1, 1, 2, 1}));
  EXPECT_EQ(mesh.group_names, (std::vector<std::string>{"", "walls", "buoy"}));
  ASSERT_EQ(mesh.materials.size(), 3u);
  EXPECT_EQ(mesh.materials[0].name, "");  // faces before any group: the default, named ""
  EXPECT_FLOAT_EQ(mesh.materials[0].backscatter, 0.5f);
  EXPECT_EQ(mesh.materials[1].name, "concrete");  // by_group applied
  EXPECT_FLOAT_EQ(mesh.materials[1].backscatter, 0.9f);
  EXPECT_FLOAT_EQ(mesh.materials[1].specular, 0.1f);
  EXPECT_EQ(mesh.materials[2].name, "buoy");  // default material, renamed after its group
  EXPECT_FLOAT_EQ(mesh.materials[2].specular, 0.3f);
}

constexpr const char* kPlyHeader = R"(ply
format %s 1.0
comment written by mesh_io_test
element vertex 4
property %s x
property %s y
property %s z
element face 2
property list uchar int vertex_indices
end_header
)";

std::string ply_header(const std::string& format, const std::string& type) {
  char header[512];
  std::snprintf(header, sizeof(header), kPlyHeader, format.c_str(), type.c_str(), type.c_str(),
                type.c_str());
  return header;
}

void expect_unit_square(const sim::TriangleMesh& mesh) {
  ASSERT_EQ(mesh.vertices_m.size(), 4u);
  EXPECT_EQ(mesh.vertices_m[2], Eigen::Vector3f(1, 1, -0.25f));
  EXPECT_EQ(mesh.triangles, (std::vector<Eigen::Vector3i>{{0, 1, 2}, {0, 2, 3}}));
  EXPECT_EQ(mesh.material_ids, (std::vector<std::uint32_t>{0, 0}));
  EXPECT_EQ(mesh.group_names, (std::vector<std::string>{""}));
  ASSERT_EQ(mesh.materials.size(), 1u);
  EXPECT_FLOAT_EQ(mesh.materials[0].backscatter, 0.5f);
}

TEST(MeshIo, PlyAscii) {
  TempDir dir;
  const std::string text = ply_header("ascii", "float") +
                           "0 0 -0.25\n1 0 -0.25\n1 1 -0.25\n0 1 -0.25\n3 0 1 2\n3 0 2 3\n";
  expect_unit_square(read_mesh(write_text(dir.file("square.ply"), text), concrete_walls()));
}

// Little-endian bytes of a value, whatever the host's byte order.
template <typename Bits, typename Value>
void append_le(std::string& out, Value value) {
  Bits bits = 0;
  std::memcpy(&bits, &value, sizeof(bits));
  for (std::size_t i = 0; i < sizeof(bits); ++i) out += static_cast<char>((bits >> (8 * i)) & 0xff);
}

TEST(MeshIo, PlyBinaryLittleEndian) {
  TempDir dir;
  std::string bytes = ply_header("binary_little_endian", "double");
  const double corners[4][2] = {{0, 0}, {1, 0}, {1, 1}, {0, 1}};
  for (const auto& corner : corners)
    for (const double value : {corner[0], corner[1], -0.25}) append_le<std::uint64_t>(bytes, value);
  const std::int32_t faces[2][3] = {{0, 1, 2}, {0, 2, 3}};
  for (const auto& face : faces) {
    bytes += '\3';  // the uchar list length
    for (const std::int32_t index : face) append_le<std::uint32_t>(bytes, index);
  }
  expect_unit_square(read_mesh(write_text(dir.file("square.ply"), bytes), concrete_walls()));
}

TEST(MeshIo, ObjRoundTripKeepsGroupsAndOrderWithinGroups) {
  sim::TriangleMesh mesh;
  mesh.vertices_m = {{0.1f, -2.5f, 1e-7f}, {123456.79f, 0, -3.3f}, {1, 1, 1}, {-0.3f, 7, 2}};
  mesh.triangles = {{0, 1, 2}, {1, 2, 3}, {0, 2, 3}, {3, 1, 0}};
  mesh.material_ids = {1, 0, 1, 0};  // interleaved: written and read back grouped
  mesh.materials = {{"bottom", 0.4f, 0.2f}, {"walls", 0.9f, 0.1f}};
  mesh.group_names = {"bottom", "walls"};
  TempDir dir;
  const std::string path = dir.file("round.obj");
  write_obj(path, mesh);
  EXPECT_EQ(read_text(path).rfind("# msislab scene\n", 0), 0u);
  const sim::TriangleMesh back = read_mesh(path, concrete_walls());
  EXPECT_EQ(back.vertices_m, mesh.vertices_m);
  EXPECT_EQ(back.group_names, mesh.group_names);
  EXPECT_EQ(back.triangles,
            (std::vector<Eigen::Vector3i>{{1, 2, 3}, {3, 1, 0}, {0, 1, 2}, {0, 2, 3}}));
  EXPECT_EQ(back.material_ids, (std::vector<std::uint32_t>{0, 0, 1, 1}));
  EXPECT_EQ(back.materials[1].name, "concrete");

  const std::string again = dir.file("again.obj");  // grouped input reads back unchanged
  write_obj(again, back);
  const sim::TriangleMesh back_again = read_mesh(again, concrete_walls());
  EXPECT_EQ(back_again.triangles, back.triangles);
  EXPECT_EQ(back_again.material_ids, back.material_ids);
}

TEST(MeshIo, MissingFiles) {
  TempDir dir;
  const std::string obj = dir.file("missing.obj"), ply = dir.file("missing.ply");
  EXPECT_EQ(error_of([&] { read_mesh(obj, MeshMaterials{}); }).rfind(obj + ": cannot open", 0), 0u);
  EXPECT_EQ(error_of([&] { read_mesh(ply, MeshMaterials{}); }).rfind(ply + ": cannot open", 0), 0u);
}

TEST(MeshIo, NoTriangles) {
  TempDir dir;
  EXPECT_EQ(mesh_error(dir, "empty.obj", ""), dir.file("empty.obj") + ": no triangles");
  EXPECT_EQ(mesh_error(dir, "points.obj", "v 0 0 0\nv 1 0 0\nv 1 1 0\n"),
            dir.file("points.obj") + ": no triangles");
  EXPECT_EQ(mesh_error(dir, "empty.ply", "").rfind(dir.file("empty.ply") + ": no triangles", 0),
            0u);
}

TEST(MeshIo, ObjErrorsNameFileAndLine) {
  TempDir dir;
  const std::string vertices = "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\n";
  EXPECT_EQ(mesh_error(dir, "quad.obj", vertices + "f 1 2 3 4\n"),
            dir.file("quad.obj") + ":5: face has 4 vertices; only triangles are supported");
  const std::string range = mesh_error(dir, "range.obj", vertices + "f 1 2 3\nf 1 2 9\n");
  EXPECT_EQ(range.rfind(dir.file("range.obj") + ":6: ", 0), 0u) << range;
  EXPECT_NE(range.find("'9' is out of range (4 vertices"), std::string::npos) << range;
  const std::string relative = mesh_error(dir, "relative.obj", vertices + "f -5 1 2\n");
  EXPECT_NE(relative.find(":5: field 2 (vertex index) '-5' is out of range"), std::string::npos)
      << relative;
  const std::string zero = mesh_error(dir, "zero.obj", vertices + "f 0 1 2\n");
  EXPECT_NE(zero.find(":5: field 2 (vertex index) '0' is invalid"), std::string::npos) << zero;
  const std::string nan = mesh_error(dir, "nan.obj", "v 0 0 0\nv 1 nan 0\n");
  EXPECT_EQ(nan, dir.file("nan.obj") + ":2: field 3 (y) 'nan' is not finite");
  const std::string statement = mesh_error(dir, "line.obj", vertices + "\n# c\nl 1 2\n");
  EXPECT_EQ(statement, dir.file("line.obj") + ":7: unsupported OBJ statement 'l'");
  const std::string slashes = mesh_error(dir, "slash.obj", vertices + "f 1/a 2 3\n");
  EXPECT_NE(slashes.find(":5: field 2 (vertex index) '1/a'"), std::string::npos) << slashes;
}

TEST(MeshIo, UnknownExtension) {
  TempDir dir;
  const std::string message = mesh_error(dir, "mesh.stl", "solid x\n");
  EXPECT_EQ(message.rfind(dir.file("mesh.stl") + ": unknown mesh format '.stl'", 0), 0u) << message;
}

TEST(MeshIo, PlyQuadRejected) {
  TempDir dir;
  const std::string text =
      ply_header("ascii", "float") + "0 0 0\n1 0 0\n1 1 0\n0 1 0\n3 0 1 2\n4 0 1 2 3\n";
  EXPECT_EQ(mesh_error(dir, "quad.ply", text),
            dir.file("quad.ply") + ": face 1 has 4 vertices; only triangles are supported");
}

TEST(MeshIo, PlyNanRejected) {
  TempDir dir;
  const std::string text =
      ply_header("ascii", "float") + "0 0 0\n1 nan 0\n1 1 0\n0 1 0\n3 0 1 2\n3 0 2 3\n";
  EXPECT_EQ(mesh_error(dir, "nan.ply", text),
            dir.file("nan.ply") + ": vertex 1 has a non-finite coordinate");
}

TEST(MeshIo, PlyGarbageRejected) {
  TempDir dir;
  const std::string message = mesh_error(dir, "garbage.ply", "this is not a ply file\n");
  EXPECT_EQ(message, dir.file("garbage.ply") + ": not a PLY file (the first line is not 'ply')");
  // A header VTK cannot parse: its complaint, on one line.
  const std::string header = mesh_error(dir, "header.ply", "ply\nformat ascii 1.0\nend_header\n");
  EXPECT_EQ(header.rfind(dir.file("header.ply") + ": ", 0), 0u) << header;
  EXPECT_EQ(header.find('\n'), std::string::npos) << header;
}

}  // namespace
}  // namespace msislab::io
