// Renderer throughput against bare Embree (target: ratio >= 1.0). On the shipped St. Pere marina
// and the stpere_replica trajectory, 4000 beams: (a) a bare rtcIntersect1 loop over exactly the
// renderer's primary rays, on an Embree scene of the same triangles and water surface; beside it
// the same rays as coherent packets of 8 and 16, the best a tracer could do on them; (b) the full
// MSIS renderer (rays, bounces, physics, speckle, noise, quantisation), counting every ray it
// casts. items_per_second is rays/s; vs_bare = (b) / (a). Two rows say where the renderer's time
// goes: its own tracer (sim::Scene, packets of 16) on the same primary rays, and the renderer
// with the optional physics off (roughness, footprints, speckle, pulse spread): what the rays,
// bounces, receive pattern, losses and bins cost without them.
#include <embree3/rtcore.h>

#include <benchmark/benchmark.h>

#include <chrono>
#include <string>
#include <vector>

#include "io/mesh_io.hpp"
#include "settings/scenario_yaml.hpp"
#include "sim/msis.hpp"
#include "sim/random.hpp"

namespace {

using namespace msislab;

const std::string kSource = MSISLAB_SOURCE_DIR;
constexpr std::size_t kBeams = 4000;

/// The replica's sonar with the optional physics switched off.
sim::Scenario lean(sim::Scenario scenario) {
  scenario.sonar.roughness_db = 0.0;
  scenario.sonar.footprint = false;
  scenario.sonar.speckle = false;
  scenario.sonar.pulse_length_us = 0.0;
  scenario.sonar.receiver_time_constant_us = 0.0;
  return scenario;
}

struct Fixture {
  sim::Scenario scenario = settings::read_scenario(kSource + "/scenarios/stpere_replica.yaml");
  sim::TriangleMesh mesh = io::read_mesh(
      scenario.scene.mesh_path,
      io::MeshMaterials{scenario.scene.default_material, scenario.scene.group_materials});
  sim::Scene scene{mesh, scenario.scene.surface};
  sim::VehicleTrajectory truth = sim::follow_path(scenario.vehicle);
  sim::MsisModel model{scene, scenario.sonar, scenario.vehicle.depth_m};
  sim::MsisModel lean_model{scene, lean(scenario).sonar, scenario.vehicle.depth_m};
  std::vector<sim::BeamSlot> slots;
  Fixture() {
    const auto all = sim::beam_schedule(scenario.sonar, truth.start_s(), truth.end_s());
    slots.assign(all.begin() + 2000, all.begin() + 2000 + kBeams);
  }
};

const Fixture& fixture() {
  static const Fixture f;
  return f;
}

double g_bare_rays_per_s = 0.0;

/// The renderer's primary rays of every benchmarked beam, in order.
std::vector<sim::Ray> renderer_primary_rays(const Fixture& f) {
  std::vector<sim::Ray> rays;
  for (const auto& slot : f.slots) {
    const auto beam_rays = f.model.primary_rays(slot, f.truth);
    rays.insert(rays.end(), beam_rays.begin(), beam_rays.end());
  }
  return rays;
}

/// An Embree scene of the mesh plus the same water-surface quad sim::Scene adds.
RTCScene bare_scene(RTCDevice device, const sim::TriangleMesh& mesh) {
  Eigen::AlignedBox3f box;
  for (const auto& v : mesh.vertices_m) box.extend(v);
  std::vector<Eigen::Vector3f> vertices = mesh.vertices_m;
  std::vector<Eigen::Vector3i> triangles = mesh.triangles;
  const float m = 50.0f;
  const int n = static_cast<int>(vertices.size());
  vertices.push_back({box.min().x() - m, box.min().y() - m, 0});
  vertices.push_back({box.max().x() + m, box.min().y() - m, 0});
  vertices.push_back({box.max().x() + m, box.max().y() + m, 0});
  vertices.push_back({box.min().x() - m, box.max().y() + m, 0});
  triangles.push_back({n, n + 1, n + 2});
  triangles.push_back({n, n + 2, n + 3});
  RTCScene scene = rtcNewScene(device);
  rtcSetSceneFlags(scene, RTC_SCENE_FLAG_ROBUST);
  RTCGeometry geometry = rtcNewGeometry(device, RTC_GEOMETRY_TYPE_TRIANGLE);
  auto* vb = static_cast<float*>(rtcSetNewGeometryBuffer(
      geometry, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3, 3 * sizeof(float), vertices.size()));
  for (std::size_t i = 0; i < vertices.size(); ++i) {
    for (int k = 0; k < 3; ++k) vb[3 * i + k] = vertices[i][k];
  }
  auto* ib = static_cast<unsigned*>(rtcSetNewGeometryBuffer(geometry, RTC_BUFFER_TYPE_INDEX, 0,
                                                            RTC_FORMAT_UINT3, 3 * sizeof(unsigned),
                                                            triangles.size()));
  for (std::size_t i = 0; i < triangles.size(); ++i) {
    for (int k = 0; k < 3; ++k) ib[3 * i + k] = static_cast<unsigned>(triangles[i][k]);
  }
  rtcCommitGeometry(geometry);
  rtcAttachGeometry(scene, geometry);
  rtcReleaseGeometry(geometry);
  rtcCommitScene(scene);
  return scene;
}

void BM_BareEmbreeOnTheRenderersRays(benchmark::State& state) {
  const Fixture& f = fixture();
  const std::vector<sim::Ray> rays = renderer_primary_rays(f);
  RTCDevice device = rtcNewDevice(nullptr);
  RTCScene scene = bare_scene(device, f.mesh);
  RTCIntersectContext context;
  float checksum = 0.0f;
  const auto t0 = std::chrono::steady_clock::now();
  for (auto _ : state) {
    for (const sim::Ray& ray : rays) {
      rtcInitIntersectContext(&context);
      RTCRayHit rh{};
      rh.ray.org_x = ray.origin_m.x();
      rh.ray.org_y = ray.origin_m.y();
      rh.ray.org_z = ray.origin_m.z();
      rh.ray.dir_x = ray.direction.x();
      rh.ray.dir_y = ray.direction.y();
      rh.ray.dir_z = ray.direction.z();
      rh.ray.tfar = ray.t_max_m;
      rh.ray.mask = ~0u;
      rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
      rtcIntersect1(scene, &context, &rh);
      checksum += rh.ray.tfar;
    }
  }
  const double elapsed_s =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  benchmark::DoNotOptimize(checksum);
  rtcReleaseScene(scene);
  rtcReleaseDevice(device);
  const auto total = static_cast<double>(state.iterations()) * static_cast<double>(rays.size());
  state.SetItemsProcessed(static_cast<std::int64_t>(total));
  g_bare_rays_per_s = total / elapsed_s;
}

/// The same rays as packets of N with the coherent hint: the best a tracer of these rays could
/// do on this scene (reported beside the single-ray figure).
template <int N, typename RayHitN>
void packet_loop(benchmark::State& state,
                 void (*intersect)(const int*, RTCScene, RTCIntersectContext*, RayHitN*)) {
  const Fixture& f = fixture();
  const std::vector<sim::Ray> rays = renderer_primary_rays(f);
  RTCDevice device = rtcNewDevice(nullptr);
  RTCScene scene = bare_scene(device, f.mesh);
  RTCIntersectContext context;
  float checksum = 0.0f;
  for (auto _ : state) {
    for (std::size_t first = 0; first < rays.size(); first += N) {
      alignas(64) int valid[N];
      alignas(64) RayHitN rh;
      for (int lane = 0; lane < N; ++lane) {
        const std::size_t i = std::min(first + static_cast<std::size_t>(lane), rays.size() - 1);
        valid[lane] = first + static_cast<std::size_t>(lane) < rays.size() ? -1 : 0;
        rh.ray.org_x[lane] = rays[i].origin_m.x();
        rh.ray.org_y[lane] = rays[i].origin_m.y();
        rh.ray.org_z[lane] = rays[i].origin_m.z();
        rh.ray.dir_x[lane] = rays[i].direction.x();
        rh.ray.dir_y[lane] = rays[i].direction.y();
        rh.ray.dir_z[lane] = rays[i].direction.z();
        rh.ray.tnear[lane] = 0.0f;
        rh.ray.tfar[lane] = rays[i].t_max_m;
        rh.ray.time[lane] = 0.0f;
        rh.ray.mask[lane] = ~0u;
        rh.ray.id[lane] = 0;
        rh.ray.flags[lane] = 0;
        rh.hit.geomID[lane] = RTC_INVALID_GEOMETRY_ID;
      }
      rtcInitIntersectContext(&context);
      context.flags = RTC_INTERSECT_CONTEXT_FLAG_COHERENT;
      intersect(valid, scene, &context, &rh);
      for (int lane = 0; lane < N; ++lane) checksum += rh.ray.tfar[lane];
    }
  }
  benchmark::DoNotOptimize(checksum);
  rtcReleaseScene(scene);
  rtcReleaseDevice(device);
  state.SetItemsProcessed(static_cast<std::int64_t>(state.iterations()) *
                          static_cast<std::int64_t>(rays.size()));
}

void BM_BareEmbreePackets8(benchmark::State& state) {
  packet_loop<8, RTCRayHit8>(state, rtcIntersect8);
}
void BM_BareEmbreePackets16(benchmark::State& state) {
  packet_loop<16, RTCRayHit16>(state, rtcIntersect16);
}

/// The renderer's own tracer (sim::Scene::intersect, packets of 16, hits with their normals and
/// materials) on the same primary rays, a beam at a time as the renderer casts them.
void BM_SceneTracerOnTheRenderersRays(benchmark::State& state) {
  const Fixture& f = fixture();
  std::vector<std::vector<sim::Ray>> beams;
  for (const auto& slot : f.slots) beams.push_back(f.model.primary_rays(slot, f.truth));
  std::vector<sim::RayHit> hits;
  float checksum = 0.0f;
  std::int64_t rays = 0;
  for (auto _ : state) {
    for (const auto& beam : beams) {
      f.scene.intersect(beam, hits);
      for (const sim::RayHit& hit : hits) checksum += hit.distance_m;
      rays += static_cast<std::int64_t>(beam.size());
    }
  }
  benchmark::DoNotOptimize(checksum);
  state.SetItemsProcessed(rays);
}

void render_loop(benchmark::State& state, const sim::MsisModel& model) {
  const Fixture& f = fixture();
  std::int64_t rays = 0;
  const auto t0 = std::chrono::steady_clock::now();
  for (auto _ : state) {
    for (const auto& slot : f.slots) {
      sim::Rng rng = sim::make_rng(1, sim::RandomStream::kSonarBeam, slot.index);
      const sim::RenderedBeam beam = model.render(slot, f.truth, rng);
      rays += beam.rays_cast;
    }
  }
  const double elapsed_s =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  state.SetItemsProcessed(rays);
  if (g_bare_rays_per_s > 0.0) {
    state.counters["vs_bare"] = static_cast<double>(rays) / elapsed_s / g_bare_rays_per_s;
  }
  state.counters["rays_per_beam"] =
      static_cast<double>(rays) / static_cast<double>(state.iterations() * kBeams);
}

void BM_MsisRenderer(benchmark::State& state) { render_loop(state, fixture().model); }
void BM_MsisRendererLeanPhysics(benchmark::State& state) {
  render_loop(state, fixture().lean_model);
}

}  // namespace

BENCHMARK(BM_BareEmbreeOnTheRenderersRays)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_BareEmbreePackets8)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_BareEmbreePackets16)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_SceneTracerOnTheRenderersRays)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_MsisRenderer)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_MsisRendererLeanPhysics)->Unit(benchmark::kMillisecond);
