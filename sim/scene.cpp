#include "sim/scene.hpp"

#include <embree3/rtcore.h>

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <memory>
#include <mutex>
#include <stdexcept>
#include <string>

namespace msislab::sim {
// The types Scene::Embree holds live in a named namespace of this file, not the anonymous one: a
// member of a class with linkage may not have a type without (GCC's -Wsubobject-linkage, which a
// unity build, compiling this file as an included one, would raise).
namespace scene_detail {

// Embree handles, released in reverse order of creation (geometry, scene, device) by RAII.
struct DeviceRelease {
  void operator()(RTCDevice device) const { rtcReleaseDevice(device); }
};
struct SceneRelease {
  void operator()(RTCScene scene) const { rtcReleaseScene(scene); }
};
struct GeometryRelease {
  void operator()(RTCGeometry geometry) const { rtcReleaseGeometry(geometry); }
};
using DeviceHandle = std::unique_ptr<RTCDeviceTy, DeviceRelease>;
using SceneHandle = std::unique_ptr<RTCSceneTy, SceneRelease>;
using GeometryHandle = std::unique_ptr<RTCGeometryTy, GeometryRelease>;

// The one device error callback: keeps the first error so that the build steps can be checked
// once instead of after every Embree call.
class ErrorLog {
 public:
  static void record(void* user, RTCError code, const char* message) {
    auto& log = *static_cast<ErrorLog*>(user);
    const std::lock_guard<std::mutex> lock(log.mutex_);
    if (log.code_ != RTC_ERROR_NONE) return;
    log.code_ = code;
    log.message_ = message != nullptr ? message : "unknown error";
  }

  void throw_if_any(const std::string& step) const {
    const std::lock_guard<std::mutex> lock(mutex_);
    if (code_ == RTC_ERROR_NONE) return;
    throw std::runtime_error("Embree error while " + step + ": " + message_ + " (code " +
                             std::to_string(static_cast<int>(code_)) + ")");
  }

 private:
  mutable std::mutex mutex_;
  RTCError code_ = RTC_ERROR_NONE;
  std::string message_;
};

}  // namespace scene_detail

using scene_detail::DeviceHandle;
using scene_detail::ErrorLog;
using scene_detail::GeometryHandle;
using scene_detail::SceneHandle;

namespace {

constexpr int kPacketSize = 16;

// The BVH is built once from valid data, so a bad mesh is a programming error caught here rather
// than a crash inside Embree.
void check_mesh(const TriangleMesh& mesh) {
  if (mesh.triangles.empty()) throw std::invalid_argument("Scene: the mesh has no triangles");
  if (mesh.material_ids.size() != mesh.triangles.size())
    throw std::invalid_argument("Scene: material_ids and triangles differ in size");
  const auto vertex_count = static_cast<int>(mesh.vertices_m.size());
  for (const Eigen::Vector3i& triangle : mesh.triangles)
    if (triangle.minCoeff() < 0 || triangle.maxCoeff() >= vertex_count)
      throw std::invalid_argument("Scene: a triangle's vertex index is out of range");
  for (const std::uint32_t id : mesh.material_ids)
    if (id >= mesh.materials.size())
      throw std::invalid_argument("Scene: a material id is out of range");
}

// The water surface: two triangles at z = 0, counter-clockwise seen from above (normal up).
void append_surface(const Eigen::AlignedBox3f& bounds, float margin_m,
                    std::vector<Eigen::Vector3f>& vertices_m,
                    std::vector<Eigen::Vector3i>& triangles) {
  const float x0 = bounds.min().x() - margin_m, x1 = bounds.max().x() + margin_m;
  const float y0 = bounds.min().y() - margin_m, y1 = bounds.max().y() + margin_m;
  const int first = static_cast<int>(vertices_m.size());
  vertices_m.emplace_back(x0, y0, 0.0f);
  vertices_m.emplace_back(x1, y0, 0.0f);
  vertices_m.emplace_back(x1, y1, 0.0f);
  vertices_m.emplace_back(x0, y1, 0.0f);
  triangles.emplace_back(first, first + 1, first + 2);
  triangles.emplace_back(first, first + 2, first + 3);
}

// Embree-owned (copied) buffers: no lifetime tie to the caller's mesh.
GeometryHandle make_triangle_geometry(RTCDevice device,
                                      const std::vector<Eigen::Vector3f>& vertices_m,
                                      const std::vector<Eigen::Vector3i>& triangles) {
  GeometryHandle geometry(rtcNewGeometry(device, RTC_GEOMETRY_TYPE_TRIANGLE));
  if (!geometry) return geometry;
  auto* vertex_buffer = static_cast<float*>(
      rtcSetNewGeometryBuffer(geometry.get(), RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3,
                              3 * sizeof(float), vertices_m.size()));
  auto* index_buffer = static_cast<unsigned*>(
      rtcSetNewGeometryBuffer(geometry.get(), RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3,
                              3 * sizeof(unsigned), triangles.size()));
  if (vertex_buffer == nullptr || index_buffer == nullptr) return nullptr;
  for (std::size_t i = 0; i < vertices_m.size(); ++i)
    for (int axis = 0; axis < 3; ++axis) vertex_buffer[3 * i + axis] = vertices_m[i][axis];
  for (std::size_t i = 0; i < triangles.size(); ++i)
    for (int corner = 0; corner < 3; ++corner)
      index_buffer[3 * i + corner] = static_cast<unsigned>(triangles[i][corner]);
  rtcSetGeometryBuildQuality(geometry.get(), RTC_BUILD_QUALITY_HIGH);
  rtcCommitGeometry(geometry.get());
  return geometry;
}

RTCRay to_embree(const Ray& ray) {
  RTCRay out{};  // tnear = 0, time = 0, id = 0, flags = 0
  out.org_x = ray.origin_m.x();
  out.org_y = ray.origin_m.y();
  out.org_z = ray.origin_m.z();
  out.dir_x = ray.direction.x();
  out.dir_y = ray.direction.y();
  out.dir_z = ray.direction.z();
  out.tfar = ray.t_max_m;
  out.mask = ~0u;
  return out;
}

// Shared by the single and the packet paths so that both answer a ray identically.
RayHit make_hit(float tfar_m, const Eigen::Vector3f& normal_unscaled,
                const Eigen::Vector3f& direction, std::uint32_t material_id,
                std::uint32_t surface_material_id) {
  RayHit hit;
  hit.hit = true;
  hit.distance_m = tfar_m;
  hit.normal = normal_unscaled.normalized();
  if (hit.normal.dot(direction) > 0.0f) hit.normal = -hit.normal;
  hit.material_id = material_id;
  hit.water_surface = material_id == surface_material_id;
  return hit;
}

// Lanes at and beyond `count` are switched off in `valid`; they repeat the last ray so that Embree
// never reads uninitialised data.
void load_packet(const Ray* rays, int count, int* valid, RTCRayHit16& packet) {
  for (int lane = 0; lane < kPacketSize; ++lane) {
    valid[lane] = lane < count ? -1 : 0;
    const RTCRay ray = to_embree(rays[std::min(lane, count - 1)]);
    packet.ray.org_x[lane] = ray.org_x;
    packet.ray.org_y[lane] = ray.org_y;
    packet.ray.org_z[lane] = ray.org_z;
    packet.ray.dir_x[lane] = ray.dir_x;
    packet.ray.dir_y[lane] = ray.dir_y;
    packet.ray.dir_z[lane] = ray.dir_z;
    packet.ray.tnear[lane] = ray.tnear;
    packet.ray.tfar[lane] = ray.tfar;
    packet.ray.time[lane] = ray.time;
    packet.ray.mask[lane] = ray.mask;
    packet.ray.id[lane] = ray.id;
    packet.ray.flags[lane] = ray.flags;
    packet.hit.geomID[lane] = RTC_INVALID_GEOMETRY_ID;
    packet.hit.instID[0][lane] = RTC_INVALID_GEOMETRY_ID;
  }
}

}  // namespace

struct Scene::Embree {
  // Declared before the device so that it outlives the device whose callback points at it.
  ErrorLog errors;
  DeviceHandle device;
  SceneHandle scene;
};

Scene::Scene(const TriangleMesh& mesh, const Material& surface_material, float surface_margin_m)
    : embree_(std::make_unique<Embree>()), materials_(mesh.materials) {
  check_mesh(mesh);
  for (const Eigen::Vector3f& vertex_m : mesh.vertices_m) bounds_.extend(vertex_m);
  const auto surface_material_id = static_cast<std::uint32_t>(materials_.size());
  materials_.push_back(surface_material);

  // One geometry holds the mesh followed by the surface's two triangles, so a hit's primitive id
  // indexes triangle_material_ directly.
  std::vector<Eigen::Vector3f> vertices_m = mesh.vertices_m;
  std::vector<Eigen::Vector3i> triangles = mesh.triangles;
  append_surface(bounds_, surface_margin_m, vertices_m, triangles);
  triangle_material_ = mesh.material_ids;
  triangle_material_.resize(triangles.size(), surface_material_id);

  Embree& embree = *embree_;
  // Embree picks its kernels by the CPU, and its SSE, AVX2 and AVX-512 kernels give hits that
  // differ in the last bits, so the same seed gave other bytes on another CPU. Capped at AVX2,
  // every CPU with AVX2 traces the same bits (docs/simulator.md, "Determinism").
  embree.device.reset(rtcNewDevice("max_isa=avx2"));
  if (!embree.device)
    throw std::runtime_error("Embree error while creating the device (code " +
                             std::to_string(static_cast<int>(rtcGetDeviceError(nullptr))) + ")");
  rtcSetDeviceErrorFunction(embree.device.get(), &ErrorLog::record, &embree.errors);
  embree.scene.reset(rtcNewScene(embree.device.get()));
  embree.errors.throw_if_any("creating the scene");
  rtcSetSceneFlags(embree.scene.get(), RTC_SCENE_FLAG_ROBUST);
  rtcSetSceneBuildQuality(embree.scene.get(), RTC_BUILD_QUALITY_HIGH);
  const GeometryHandle geometry =
      make_triangle_geometry(embree.device.get(), vertices_m, triangles);
  embree.errors.throw_if_any("creating the triangle geometry");
  if (!geometry) throw std::runtime_error("Embree could not create the triangle geometry");
  rtcAttachGeometry(embree.scene.get(), geometry.get());
  rtcCommitScene(embree.scene.get());
  embree.errors.throw_if_any("building the BVH");
}

Scene::~Scene() = default;

RayHit Scene::intersect(const Ray& ray) const {
  RTCIntersectContext context;
  rtcInitIntersectContext(&context);
  RTCRayHit ray_hit{};
  ray_hit.ray = to_embree(ray);
  ray_hit.hit.geomID = RTC_INVALID_GEOMETRY_ID;
  ray_hit.hit.instID[0] = RTC_INVALID_GEOMETRY_ID;
  rtcIntersect1(embree_->scene.get(), &context, &ray_hit);
  if (ray_hit.hit.geomID == RTC_INVALID_GEOMETRY_ID) return RayHit{};
  const Eigen::Vector3f normal(ray_hit.hit.Ng_x, ray_hit.hit.Ng_y, ray_hit.hit.Ng_z);
  return make_hit(ray_hit.ray.tfar, normal, ray.direction, triangle_material_[ray_hit.hit.primID],
                  static_cast<std::uint32_t>(materials_.size() - 1));
}

void Scene::intersect(const std::vector<Ray>& rays, std::vector<RayHit>& hits) const {
  hits.resize(rays.size());
  RTCIntersectContext context;
  rtcInitIntersectContext(&context);
  const auto surface_material_id = static_cast<std::uint32_t>(materials_.size() - 1);
  for (std::size_t first = 0; first < rays.size(); first += kPacketSize) {
    const int count = static_cast<int>(std::min<std::size_t>(kPacketSize, rays.size() - first));
    alignas(64) int valid[kPacketSize];
    RTCRayHit16 packet;
    load_packet(rays.data() + first, count, valid, packet);
    rtcIntersect16(valid, embree_->scene.get(), &context, &packet);
    for (int lane = 0; lane < count; ++lane) {
      const Ray& ray = rays[first + static_cast<std::size_t>(lane)];
      RayHit& hit = hits[first + static_cast<std::size_t>(lane)];
      if (packet.hit.geomID[lane] == RTC_INVALID_GEOMETRY_ID) {
        hit = RayHit{};
        continue;
      }
      const Eigen::Vector3f normal(packet.hit.Ng_x[lane], packet.hit.Ng_y[lane],
                                   packet.hit.Ng_z[lane]);
      hit = make_hit(packet.ray.tfar[lane], normal, ray.direction,
                     triangle_material_[packet.hit.primID[lane]], surface_material_id);
    }
  }
}

}  // namespace msislab::sim
