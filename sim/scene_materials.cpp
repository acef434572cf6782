#include "sim/scene_materials.hpp"

#include <cmath>
#include <map>

#include "geometry/angles.hpp"
#include "sim/scene.hpp"

namespace msislab::sim {
namespace {

/// Twice the area times the unit normal (the cross product of two edges).
Eigen::Vector3f area_normal(const TriangleMesh& mesh, std::size_t i) {
  const Eigen::Vector3i& t = mesh.triangles[i];
  const Eigen::Vector3f& a = mesh.vertices_m[static_cast<std::size_t>(t[0])];
  const Eigen::Vector3f& b = mesh.vertices_m[static_cast<std::size_t>(t[1])];
  const Eigen::Vector3f& c = mesh.vertices_m[static_cast<std::size_t>(t[2])];
  return (b - a).cross(c - a);
}

Eigen::Vector3f centre(const TriangleMesh& mesh, std::size_t i) {
  const Eigen::Vector3i& t = mesh.triangles[i];
  return (mesh.vertices_m[static_cast<std::size_t>(t[0])] +
          mesh.vertices_m[static_cast<std::size_t>(t[1])] +
          mesh.vertices_m[static_cast<std::size_t>(t[2])]) /
         3.0f;
}

/// |cos| of the angle between a face's normal and the vertical; -1 for a degenerate face.
float vertical_cosine(const TriangleMesh& mesh, std::size_t i) {
  const Eigen::Vector3f n = area_normal(mesh, i);
  const float length = n.norm();
  return length > 1e-12f ? std::abs(n.z()) / length : -1.0f;
}

}  // namespace

std::vector<bool> bottom_faces(const TriangleMesh& mesh) {
  std::vector<bool> out(mesh.triangles.size(), false);
  const float min_cos = static_cast<float>(std::cos(kMaxBottomTilt_deg * kPi / 180.0));
  std::vector<Ray> rays;
  std::vector<std::size_t> candidates;
  for (std::size_t i = 0; i < mesh.triangles.size(); ++i) {
    if (vertical_cosine(mesh, i) < min_cos) continue;
    // Straight down from just under the face's centre: anything hit (another face, or the water
    // surface for a face above it) lies under this one.
    Ray down;
    down.origin_m = centre(mesh, i) - Eigen::Vector3f(0.0f, 0.0f, 1e-3f);
    down.direction = -Eigen::Vector3f::UnitZ();
    rays.push_back(down);
    candidates.push_back(i);
  }
  if (candidates.empty()) return out;
  const Scene scene(mesh, Material{"water_surface", 0.0f, 0.0f});
  std::vector<RayHit> hits;
  scene.intersect(rays, hits);
  for (std::size_t k = 0; k < candidates.size(); ++k) out[candidates[k]] = !hits[k].hit;
  return out;
}

void assign_bottom_material(TriangleMesh& mesh, const std::vector<bool>& is_bottom,
                            const std::set<std::string>& explicit_groups, const Material& bottom) {
  // Per material: how many of its faces are floor, and how many are not.
  std::vector<std::size_t> floor(mesh.materials.size(), 0), other(mesh.materials.size(), 0);
  for (std::size_t i = 0; i < mesh.triangles.size(); ++i) {
    (is_bottom[i] ? floor : other)[mesh.material_ids[i]] += 1;
  }
  std::map<std::uint32_t, std::uint32_t> floor_id;  // material id -> its floor's material id
  const std::size_t count = mesh.materials.size();
  for (std::size_t m = 0; m < count; ++m) {
    const std::string& group = mesh.group_names[m];
    if (floor[m] == 0 || explicit_groups.count(group) != 0) continue;
    Material material = bottom;
    if (other[m] == 0) {
      material.name = mesh.materials[m].name;
      mesh.materials[m] = material;
      continue;
    }
    material.name = group.empty() ? "bottom" : group + "/bottom";
    floor_id[static_cast<std::uint32_t>(m)] = static_cast<std::uint32_t>(mesh.materials.size());
    mesh.materials.push_back(material);
    mesh.group_names.push_back(group);
  }
  for (std::size_t i = 0; i < mesh.triangles.size(); ++i) {
    const auto found = floor_id.find(mesh.material_ids[i]);
    if (is_bottom[i] && found != floor_id.end()) mesh.material_ids[i] = found->second;
  }
}

SurfaceBrightness surface_brightness(const TriangleMesh& mesh, const std::vector<bool>& is_bottom) {
  SurfaceBrightness out;
  const float max_wall_cos = static_cast<float>(std::sin(kMaxBottomTilt_deg * kPi / 180.0));
  double bottom_sum = 0.0, walls_sum = 0.0;
  for (std::size_t i = 0; i < mesh.triangles.size(); ++i) {
    const double area_m2 = 0.5 * static_cast<double>(area_normal(mesh, i).norm());
    const double backscatter = mesh.materials[mesh.material_ids[i]].backscatter;
    const float cos_vertical = vertical_cosine(mesh, i);
    if (is_bottom[i]) {
      out.bottom_area_m2 += area_m2;
      bottom_sum += area_m2 * backscatter;
    } else if (cos_vertical >= 0.0f && cos_vertical <= max_wall_cos) {
      out.walls_area_m2 += area_m2;
      walls_sum += area_m2 * backscatter;
    }
  }
  if (out.bottom_area_m2 > 0.0) out.bottom_backscatter = bottom_sum / out.bottom_area_m2;
  if (out.walls_area_m2 > 0.0) out.walls_backscatter = walls_sum / out.walls_area_m2;
  return out;
}

bool bottom_as_bright_as_walls(const SurfaceBrightness& b) {
  if (b.bottom_area_m2 <= 0.0 || b.walls_area_m2 <= 0.0) return false;
  return b.bottom_backscatter >=
         b.walls_backscatter * std::pow(10.0, -kMinBottomContrast_dB / 10.0);
}

}  // namespace msislab::sim
