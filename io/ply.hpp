// PLY, the one reader for every PLY msislab reads (scene meshes and map.ply point clouds): ASCII,
// binary little and big endian, any elements and properties. Kept are the vertex element's x, y
// and z and the face element's vertex_indices (or vertex_index) lists; every other element and
// property is read past. Strict: errors name the file and, in the header and ASCII data, the line
// ("path:line: what"); a file shorter than its header announces is an error, never zeros.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include <Eigen/Core>

namespace msislab::io {

struct PlyData {
  std::vector<Eigen::Vector3d> vertices_m;  ///< z = 0 when the file has no z property
  std::vector<std::vector<std::int64_t>> faces;
};

/// Reads a PLY file; every vertex coordinate is finite ("vertex 3 has a non-finite coordinate").
PlyData read_ply(const std::string& path);

}  // namespace msislab::io
