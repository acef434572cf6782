// Ray casting speed of sim::Scene against bare Embree, on a procedural marina (a 130 x 60 m basin
// 3.3 m deep with a 200 m canal, bottom and pilings; 6,328 triangles) and the SAME 1,000,000
// random rays from inside the basin for every case. items_per_second is rays/s; vs_bare is the
// ratio to the bare rtcIntersect1 loop (the reference), when that case ran first.
#include <embree3/rtcore.h>

#include <benchmark/benchmark.h>

#include <cmath>
#include <cstddef>
#include <ctime>
#include <random>
#include <stdexcept>
#include <vector>

#include "sim/mesh.hpp"
#include "sim/scene.hpp"

namespace {

using msislab::sim::Ray;
using msislab::sim::RayHit;
using msislab::sim::TriangleMesh;

constexpr std::size_t kRayCount = 1'000'000;
constexpr float kDepthM = 3.3f;
constexpr float kSurfaceMarginM = 50.0f;  // Scene's default
constexpr float kPi = 3.14159265358979f;

// A grid of nu x nv quads (two triangles each) spanning corner + [0, 1] u + [0, 1] v.
void add_grid(TriangleMesh& mesh, const Eigen::Vector3f& corner, const Eigen::Vector3f& u,
              const Eigen::Vector3f& v, int nu, int nv, std::uint32_t material) {
  const int first = static_cast<int>(mesh.vertices_m.size());
  for (int j = 0; j <= nv; ++j)
    for (int i = 0; i <= nu; ++i)
      mesh.vertices_m.push_back(corner + u * (static_cast<float>(i) / static_cast<float>(nu)) +
                                v * (static_cast<float>(j) / static_cast<float>(nv)));
  for (int j = 0; j < nv; ++j)
    for (int i = 0; i < nu; ++i) {
      const int a = first + j * (nu + 1) + i, b = a + 1, c = a + nu + 1, d = c + 1;
      mesh.triangles.emplace_back(a, b, d);
      mesh.triangles.emplace_back(a, d, c);
      mesh.material_ids.insert(mesh.material_ids.end(), 2, material);
    }
}

// A vertical quay wall from the surface to the bottom along (x0, y0) -> (x1, y1), 1 m panels.
void add_wall(TriangleMesh& mesh, float x0, float y0, float x1, float y1) {
  const Eigen::Vector3f from(x0, y0, -kDepthM), along(x1 - x0, y1 - y0, 0.0f);
  add_grid(mesh, from, along, Eigen::Vector3f(0, 0, kDepthM), static_cast<int>(along.norm()), 3, 0);
}

// An octagonal piling of radius 0.25 m from the bottom to the surface.
void add_piling(TriangleMesh& mesh, float x, float y) {
  constexpr int kSides = 8;
  constexpr float kRadiusM = 0.25f;
  for (int side = 0; side < kSides; ++side) {
    const float a0 = 2.0f * kPi * static_cast<float>(side) / kSides;
    const float a1 = 2.0f * kPi * static_cast<float>(side + 1) / kSides;
    const Eigen::Vector3f p0(x + kRadiusM * std::cos(a0), y + kRadiusM * std::sin(a0), -kDepthM);
    const Eigen::Vector3f p1(x + kRadiusM * std::cos(a1), y + kRadiusM * std::sin(a1), -kDepthM);
    add_grid(mesh, p0, p1 - p0, Eigen::Vector3f(0, 0, kDepthM), 1, 1, 2);
  }
}

TriangleMesh marina() {
  TriangleMesh mesh;
  mesh.materials = {{"quay", 0.8f, 0.3f}, {"mud", 0.3f, 0.05f}, {"piling", 0.9f, 0.4f}};
  mesh.group_names = {"quay", "mud", "piling"};
  add_grid(mesh, {0, 0, -kDepthM}, {130, 0, 0}, {0, 60, 0}, 26, 12, 1);    // basin bottom
  add_grid(mesh, {130, 20, -kDepthM}, {200, 0, 0}, {0, 20, 0}, 40, 4, 1);  // canal bottom
  add_wall(mesh, 0, 0, 130, 0);
  add_wall(mesh, 0, 60, 130, 60);
  add_wall(mesh, 0, 0, 0, 60);
  add_wall(mesh, 130, 0, 130, 20);  // the east wall, open to the canal between y = 20 and 40
  add_wall(mesh, 130, 40, 130, 60);
  add_wall(mesh, 130, 20, 330, 20);
  add_wall(mesh, 130, 40, 330, 40);
  add_wall(mesh, 330, 20, 330, 40);
  for (float x = 10; x <= 115; x += 5) {  // two pontoon lines
    add_piling(mesh, x, 20);
    add_piling(mesh, x, 40);
  }
  return mesh;
}

std::vector<Ray> random_rays() {
  std::mt19937 generator(42);
  std::uniform_real_distribution<float> x_m(2, 128), y_m(2, 58), z_m(-kDepthM + 0.3f, -0.3f);
  std::normal_distribution<float> gaussian(0.0f, 1.0f);
  std::vector<Ray> rays(kRayCount);
  for (Ray& ray : rays) {
    ray.origin_m = {x_m(generator), y_m(generator), z_m(generator)};
    ray.direction =
        Eigen::Vector3f(gaussian(generator), gaussian(generator), gaussian(generator)).normalized();
  }
  return rays;
}

// The reference: the mesh plus the same surface rectangle in a plain Embree scene, no wrapper.
class BareEmbree {
 public:
  explicit BareEmbree(const TriangleMesh& mesh) : device_(rtcNewDevice(nullptr)) {
    if (device_ == nullptr) throw std::runtime_error("rtcNewDevice failed");
    scene_ = rtcNewScene(device_);
    rtcSetSceneFlags(scene_, RTC_SCENE_FLAG_ROBUST);  // as sim::Scene, so only the wrapper differs
    rtcSetSceneBuildQuality(scene_, RTC_BUILD_QUALITY_HIGH);
    RTCGeometry geometry = rtcNewGeometry(device_, RTC_GEOMETRY_TYPE_TRIANGLE);
    fill(geometry, mesh);
    rtcSetGeometryBuildQuality(geometry, RTC_BUILD_QUALITY_HIGH);
    rtcCommitGeometry(geometry);
    rtcAttachGeometry(scene_, geometry);
    rtcReleaseGeometry(geometry);
    rtcCommitScene(scene_);
    if (rtcGetDeviceError(device_) != RTC_ERROR_NONE) throw std::runtime_error("Embree failed");
  }
  ~BareEmbree() {
    rtcReleaseScene(scene_);
    rtcReleaseDevice(device_);
  }
  BareEmbree(const BareEmbree&) = delete;
  BareEmbree& operator=(const BareEmbree&) = delete;

  RTCScene scene() const { return scene_; }

 private:
  static void fill(RTCGeometry geometry, const TriangleMesh& mesh) {
    Eigen::AlignedBox3f bounds;
    for (const auto& vertex_m : mesh.vertices_m) bounds.extend(vertex_m);
    const Eigen::Vector3f low = bounds.min().array() - kSurfaceMarginM;
    const Eigen::Vector3f high = bounds.max().array() + kSurfaceMarginM;
    std::vector<Eigen::Vector3f> vertices_m = mesh.vertices_m;
    std::vector<Eigen::Vector3i> triangles = mesh.triangles;
    const int n = static_cast<int>(vertices_m.size());
    vertices_m.insert(vertices_m.end(), {{low.x(), low.y(), 0},
                                         {high.x(), low.y(), 0},
                                         {high.x(), high.y(), 0},
                                         {low.x(), high.y(), 0}});
    triangles.insert(triangles.end(), {{n, n + 1, n + 2}, {n, n + 2, n + 3}});
    auto* vertex = static_cast<float*>(rtcSetNewGeometryBuffer(
        geometry, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3, 12, vertices_m.size()));
    auto* index = static_cast<int*>(rtcSetNewGeometryBuffer(
        geometry, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3, 12, triangles.size()));
    for (std::size_t i = 0; i < vertices_m.size(); ++i)
      for (int k = 0; k < 3; ++k) vertex[3 * i + k] = vertices_m[i][k];
    for (std::size_t i = 0; i < triangles.size(); ++i)
      for (int k = 0; k < 3; ++k) index[3 * i + k] = triangles[i][k];
  }

  RTCDevice device_;
  RTCScene scene_ = nullptr;
};

struct Fixture {
  TriangleMesh mesh = marina();
  std::vector<Ray> rays = random_rays();
  msislab::sim::Scene scene{mesh, msislab::sim::Material{"surface", 0.1f, 0.9f}};
  BareEmbree bare{mesh};
};

const Fixture& fixture() {
  static const Fixture instance;
  return instance;
}

double g_bare_rays_per_s = 0.0;

// CPU time of this thread, as Google Benchmark's items_per_second uses: the ratio stays meaningful
// when other processes share the machine.
double thread_cpu_s() {
  timespec now{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &now);
  return static_cast<double>(now.tv_sec) + 1e-9 * static_cast<double>(now.tv_nsec);
}

// Runs `cast_all` (which casts every ray once and returns the hit count) under the benchmark loop
// and reports rays/s, the hit fraction and the ratio to the bare reference.
template <typename CastAll>
void run(benchmark::State& state, CastAll cast_all, bool is_reference) {
  std::size_t hits = 0;
  const double start_s = thread_cpu_s();
  for (auto _ : state) {
    hits = cast_all();
    benchmark::DoNotOptimize(hits);
  }
  const double elapsed_s = thread_cpu_s() - start_s;
  const double rays_per_s = static_cast<double>(state.iterations() * kRayCount) / elapsed_s;
  if (is_reference) g_bare_rays_per_s = rays_per_s;
  state.SetItemsProcessed(state.iterations() * static_cast<std::int64_t>(kRayCount));
  state.counters["hit_fraction"] = static_cast<double>(hits) / kRayCount;
  if (g_bare_rays_per_s > 0.0) state.counters["vs_bare"] = rays_per_s / g_bare_rays_per_s;
}

void BM_BareEmbreeIntersect1(benchmark::State& state) {
  const Fixture& f = fixture();
  run(
      state,
      [&f] {
        RTCIntersectContext context;
        rtcInitIntersectContext(&context);
        std::size_t hits = 0;
        for (const Ray& ray : f.rays) {
          RTCRayHit ray_hit{};
          ray_hit.ray = {ray.origin_m.x(),
                         ray.origin_m.y(),
                         ray.origin_m.z(),
                         0.0f,
                         ray.direction.x(),
                         ray.direction.y(),
                         ray.direction.z(),
                         0.0f,
                         ray.t_max_m,
                         ~0u,
                         0u,
                         0u};
          ray_hit.hit.geomID = RTC_INVALID_GEOMETRY_ID;
          rtcIntersect1(f.bare.scene(), &context, &ray_hit);
          hits += ray_hit.hit.geomID != RTC_INVALID_GEOMETRY_ID ? 1 : 0;
        }
        return hits;
      },
      true);
}
BENCHMARK(BM_BareEmbreeIntersect1)->Unit(benchmark::kMillisecond);

void BM_SceneIntersectSingle(benchmark::State& state) {
  const Fixture& f = fixture();
  run(
      state,
      [&f] {
        std::size_t hits = 0;
        for (const Ray& ray : f.rays) hits += f.scene.intersect(ray).hit ? 1 : 0;
        return hits;
      },
      false);
}
BENCHMARK(BM_SceneIntersectSingle)->Unit(benchmark::kMillisecond);

void BM_SceneIntersectBulk(benchmark::State& state) {
  const Fixture& f = fixture();
  std::vector<RayHit> results(kRayCount);
  run(
      state,
      [&f, &results] {
        f.scene.intersect(f.rays, results);
        std::size_t hits = 0;
        for (const RayHit& result : results) hits += result.hit ? 1 : 0;
        return hits;
      },
      false);
}
BENCHMARK(BM_SceneIntersectBulk)->Unit(benchmark::kMillisecond);

}  // namespace
