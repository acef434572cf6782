// The acoustic scene: a TriangleMesh in an Embree 3 BVH, plus the water surface (a horizontal
// plane at z = 0 covering the mesh), answering ray queries. Embree's device, scene and geometry are
// owned by RAII wrappers; one device error callback records errors (docs/simulator.md).
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <memory>
#include <vector>

#include "sim/mesh.hpp"

namespace msislab::sim {

struct Ray {
  Eigen::Vector3f origin_m = Eigen::Vector3f::Zero();
  Eigen::Vector3f direction = Eigen::Vector3f::UnitX();  ///< unit length
  float t_max_m = 1e30f;
};

struct RayHit {
  bool hit = false;
  float distance_m = 0.0f;                            ///< along the ray
  Eigen::Vector3f normal = Eigen::Vector3f::UnitZ();  ///< unit, facing the ray's origin side
  std::uint32_t material_id = 0;                      ///< into Scene::materials()
  bool water_surface = false;                         ///< hit the z = 0 plane
};

class Scene {
 public:
  /// Builds the BVH. The mesh must be valid (io/ checks it). The water surface is added as a
  /// plane at z = 0 over the mesh's x/y extent plus `surface_margin_m`, with `surface_material`.
  Scene(const TriangleMesh& mesh, const Material& surface_material, float surface_margin_m = 50.0f);
  ~Scene();
  Scene(const Scene&) = delete;
  Scene& operator=(const Scene&) = delete;

  /// The first surface along a ray (rtcIntersect1).
  RayHit intersect(const Ray& ray) const;
  /// Many rays at once (Embree packets of 16); hits[i] answers rays[i].
  void intersect(const std::vector<Ray>& rays, std::vector<RayHit>& hits) const;

  /// Mesh materials followed by the water surface's (the last entry).
  const std::vector<Material>& materials() const { return materials_; }
  /// Axis-aligned bounds of the mesh (without the surface plane).
  const Eigen::AlignedBox3f& bounds() const { return bounds_; }

 private:
  struct Embree;
  std::unique_ptr<Embree> embree_;
  std::vector<Material> materials_;
  std::vector<std::uint32_t> triangle_material_;  ///< per primitive, the surface's last
  Eigen::AlignedBox3f bounds_;
};

}  // namespace msislab::sim
