// The one PLY reader: ASCII, binary little and big endian, other elements and properties read
// past, and the malformed files that made VTK's reader crash, each a clear one-line error.
#include "io/ply.hpp"

#include <gtest/gtest.h>

#include <cstdint>
#include <cstring>
#include <string>

#include "io/input_error.hpp"
#include "io/mesh_io.hpp"
#include "test_support.hpp"

namespace msislab::io {
namespace {

using testing::TempDir;
using testing::write_text;

std::string error_of(const std::string& path) {
  try {
    read_ply(path);
  } catch (const InputError& e) {
    return e.what();
  }
  return "no error";
}

template <typename T>
void append_bytes(std::string& out, T value, bool big_endian) {
  char bytes[sizeof(T)];
  std::memcpy(bytes, &value, sizeof(T));
  for (std::size_t i = 0; i < sizeof(T); ++i) out += bytes[big_endian ? sizeof(T) - 1 - i : i];
}

TEST(Ply, AsciiWithOtherElementsAndProperties) {
  TempDir dir;
  const std::string path = write_text(dir.file("a.ply"),
                                      "ply\r\nformat ascii 1.0\ncomment c\nelement material 1\n"
                                      "property uchar red\nproperty list uchar float w\n"
                                      "element vertex 3\nproperty double y\nproperty int id\n"
                                      "property double x\nelement face 1\n"
                                      "property list uchar int vertex_index\nproperty float q\n"
                                      "end_header\n200 2 0.5 0.25\n1.5 7 -2\n\n0 8 1\n2 9 3\n"
                                      "3 0 1 2 0.5\n");
  const PlyData ply = read_ply(path);
  ASSERT_EQ(ply.vertices_m.size(), 3u);
  EXPECT_EQ(ply.vertices_m[0], Eigen::Vector3d(-2, 1.5, 0));
  EXPECT_EQ(ply.vertices_m[2], Eigen::Vector3d(3, 2, 0));
  EXPECT_EQ(ply.faces, (std::vector<std::vector<std::int64_t>>{{0, 1, 2}}));
}

TEST(Ply, BinaryBothByteOrders) {
  TempDir dir;
  for (const bool big : {false, true}) {
    std::string bytes = std::string("ply\nformat ") +
                        (big ? "binary_big_endian" : "binary_little_endian") +
                        " 1.0\nelement vertex 2\nproperty float x\nproperty short y\n"
                        "property double z\nelement face 1\n"
                        "property list ushort uint vertex_indices\nend_header\n";
    append_bytes<float>(bytes, 1.25f, big);
    append_bytes<std::int16_t>(bytes, -300, big);
    append_bytes<double>(bytes, 0.1, big);
    append_bytes<float>(bytes, -4.0f, big);
    append_bytes<std::int16_t>(bytes, 7, big);
    append_bytes<double>(bytes, 2.0, big);
    append_bytes<std::uint16_t>(bytes, 3, big);
    for (const std::uint32_t i : {1u, 0u, 1u}) append_bytes(bytes, i, big);
    const PlyData ply = read_ply(write_text(dir.file("b.ply"), bytes));
    SCOPED_TRACE(big);
    ASSERT_EQ(ply.vertices_m.size(), 2u);
    EXPECT_EQ(ply.vertices_m[0], Eigen::Vector3d(1.25, -300, 0.1));
    EXPECT_EQ(ply.vertices_m[1], Eigen::Vector3d(-4, 7, 2));
    EXPECT_EQ(ply.faces, (std::vector<std::vector<std::int64_t>>{{1, 0, 1}}));
  }
}

TEST(Ply, MalformedFilesAreOneLineErrors) {
  TempDir dir;
  const std::string xyz =
      "element vertex 2\nproperty float x\nproperty float y\n"
      "property float z\nend_header\n";
  const auto error = [&](const std::string& text) {
    return error_of(write_text(dir.file("m.ply"), text));
  };
  const std::string p = dir.file("m.ply");
  EXPECT_EQ(error(""), p + ": not a PLY file (the first line is not 'ply')");
  EXPECT_EQ(error("ply\nformat ascii 1.0\n"), p + ": no end_header line");
  EXPECT_EQ(error("ply\nformat utf8 1.0\n" + xyz), p + ":2: unknown format 'utf8'");
  EXPECT_EQ(error("ply\nformat ascii 1.0\nelement vertex 2\nproperty half x\nend_header\n"),
            p + ":4: unknown property type 'half'");
  EXPECT_EQ(error("ply\nformat ascii 1.0\nproperty float x\nend_header\n"),
            p + ":3: property before any element");
  EXPECT_EQ(error("ply\nformat ascii 1.0\nelement vertex -1\nend_header\n"),
            p + ":3: field 3 (count) '-1' is negative");
  EXPECT_EQ(error("ply\nformat ascii 1.0\n" + xyz + "1 2 3\n"),
            p + ": truncated: the header announces 2 vertices, the file has 1");
  EXPECT_EQ(error("ply\nformat ascii 1.0\n" + xyz + "1 2 3\n1 2\n"),
            p + ":9: truncated line: no z");
  EXPECT_EQ(error("ply\nformat ascii 1.0\n" + xyz + "1 2 3\n1 2 3 4\n"),
            p + ":9: too many columns: expected 3 columns, got 4");
  EXPECT_EQ(error("ply\nformat ascii 1.0\n" + xyz + "1 2 3\n1 x 3\n"),
            p + ":9: field 2 (y) 'x' is not a number");
  EXPECT_EQ(error("ply\nformat ascii 1.0\n" + xyz + "1 2 3\n1 inf 3\n"),
            p + ": vertex 1 has a non-finite coordinate");
  // An element without properties holds no data, however many it announces.
  EXPECT_EQ(error("ply\nformat binary_little_endian 1.0\nelement e 999999999999\n" + xyz +
                  "abcdefghijkl"),
            p + ": truncated: the header announces 2 vertices, the file has 1");
  EXPECT_EQ(error("ply\nformat binary_little_endian 1.0\n" + xyz + "abcdefghijkl"),
            p + ": truncated: the header announces 2 vertices, the file has 1");
  EXPECT_EQ(error("ply\nformat ascii 1.0\nelement face 1\nproperty list uchar int "
                  "vertex_indices\nend_header\n3 0 1 2\n"),
            p + ": no 'element vertex' with x and y properties");
  EXPECT_EQ(error("ply\nformat ascii 1.0\nelement vertex 1\nproperty float x\nproperty float y\n"
                  "element face 1\nproperty list uchar int vertex_indices\nend_header\n0 0\n"
                  "2 0.5 1\n"),
            p + ": face 0 has a vertex index that is not an integer");
}

// Each of these made vtkPLYReader (the mesh path before io/ply) crash `msislab simulate`.
TEST(Ply, FilesThatCrashedVtkAreMeshErrors) {
  TempDir dir;
  for (const std::string text :
       {"ply\nformat binary_little_endian 1.0\nelement vertex 1\nend_header\n",
        "ply\nformat ascii 1.0\nelement vertex 3\nproperty double x\nproperty double y\n"
        "end_header\n1 2\n3 4\n",
        "ply\nformat ascii 1.0\nelement vertex 1\nproperty float x\nproperty float y\n"
        "property float z\nend_header\n1 2\n"}) {
    SCOPED_TRACE(text);
    const std::string path = write_text(dir.file("crash.ply"), text);
    EXPECT_THROW(read_mesh(path, MeshMaterials{}), InputError);
  }
}

}  // namespace
}  // namespace msislab::io
