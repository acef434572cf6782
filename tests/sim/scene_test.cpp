// Scene ray queries against hand-made geometry with known answers: a wall at x = 10 m, a floor at
// z = -6 m and the water surface at z = 0. Distances are checked to 1e-4 m.
#include "sim/scene.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <stdexcept>
#include <thread>
#include <vector>

namespace msislab::sim {
namespace {

constexpr float kToleranceM = 1e-4f;
constexpr float kSurfaceMarginM = 5.0f;

// Wall x = 10 (material 0) spanning y in [-10, 10], z in [-6, -0.5]; floor z = -6 (material 1)
// over x, y in [-10, 10].
TriangleMesh wall_and_floor() {
  TriangleMesh mesh;
  mesh.vertices_m = {{10, -10, -6},  {10, 10, -6},  {10, 10, -0.5f}, {10, -10, -0.5f},
                     {-10, -10, -6}, {10, -10, -6}, {10, 10, -6},    {-10, 10, -6}};
  mesh.triangles = {{0, 1, 2}, {0, 2, 3}, {4, 5, 6}, {4, 6, 7}};
  mesh.material_ids = {0, 0, 1, 1};
  mesh.materials = {{"wall", 0.7f, 0.2f}, {"floor", 0.4f, 0.1f}};
  mesh.group_names = {"wall", "floor"};
  return mesh;
}

class SceneTest : public ::testing::Test {
 protected:
  SceneTest() : scene_(wall_and_floor(), Material{"surface", 0.1f, 0.9f}, kSurfaceMarginM) {}

  RayHit cast(const Eigen::Vector3f& origin_m, const Eigen::Vector3f& direction,
              float t_max_m = 1e30f) const {
    Ray ray;
    ray.origin_m = origin_m;
    ray.direction = direction.normalized();
    ray.t_max_m = t_max_m;
    return scene_.intersect(ray);
  }

  Scene scene_;
};

void expect_same(const RayHit& a, const RayHit& b, std::size_t index) {
  ASSERT_EQ(a.hit, b.hit) << "ray " << index;
  EXPECT_EQ(a.distance_m, b.distance_m) << "ray " << index;
  EXPECT_EQ(a.normal, b.normal) << "ray " << index;
  EXPECT_EQ(a.material_id, b.material_id) << "ray " << index;
  EXPECT_EQ(a.water_surface, b.water_surface) << "ray " << index;
}

std::vector<Ray> random_rays(std::size_t count, unsigned seed) {
  std::mt19937 generator(seed);
  std::uniform_real_distribution<float> xy_m(-16.0f, 16.0f), z_m(-7.0f, 1.0f), t_max_m(1, 40);
  std::normal_distribution<float> gaussian(0.0f, 1.0f);
  std::vector<Ray> rays(count);
  for (Ray& ray : rays) {
    ray.origin_m = {xy_m(generator), xy_m(generator), z_m(generator)};
    ray.direction =
        Eigen::Vector3f(gaussian(generator), gaussian(generator), gaussian(generator)).normalized();
    ray.t_max_m = t_max_m(generator);
  }
  return rays;
}

TEST_F(SceneTest, HitsWallHeadOn) {
  const RayHit hit = cast({0, 0, -2}, Eigen::Vector3f::UnitX());
  ASSERT_TRUE(hit.hit);
  EXPECT_NEAR(hit.distance_m, 10.0f, kToleranceM);
  EXPECT_TRUE(hit.normal.isApprox(-Eigen::Vector3f::UnitX(), 1e-6f)) << hit.normal.transpose();
  EXPECT_EQ(hit.material_id, 0u);
  EXPECT_FALSE(hit.water_surface);
}

TEST_F(SceneTest, HitsWallAtAngle) {
  const float angle_rad = 0.5f;  // y at the wall: 10 tan(0.5) = 5.46 m, inside the wall
  const Eigen::Vector3f direction(std::cos(angle_rad), std::sin(angle_rad), 0.0f);
  const RayHit hit = cast({0, 0, -2}, direction);
  ASSERT_TRUE(hit.hit);
  EXPECT_NEAR(hit.distance_m, 10.0f / std::cos(angle_rad), kToleranceM);
  EXPECT_LT(hit.normal.dot(direction), 0.0f);
  EXPECT_NEAR(hit.normal.norm(), 1.0f, 1e-6f);
  EXPECT_EQ(hit.material_id, 0u);
}

TEST_F(SceneTest, NormalFacesRayFromEitherSide) {
  const RayHit behind = cast({12, 0, -2}, -Eigen::Vector3f::UnitX());
  ASSERT_TRUE(behind.hit);
  EXPECT_NEAR(behind.distance_m, 2.0f, kToleranceM);
  EXPECT_TRUE(behind.normal.isApprox(Eigen::Vector3f::UnitX(), 1e-6f));

  const RayHit floor = cast({1, 2, -2}, -Eigen::Vector3f::UnitZ());
  ASSERT_TRUE(floor.hit);
  EXPECT_NEAR(floor.distance_m, 4.0f, kToleranceM);
  EXPECT_TRUE(floor.normal.isApprox(Eigen::Vector3f::UnitZ(), 1e-6f));
  EXPECT_EQ(floor.material_id, 1u);
}

TEST_F(SceneTest, ParallelOrAwayMisses) {
  EXPECT_FALSE(cast({0, 0, -2}, Eigen::Vector3f::UnitY()).hit);   // parallel to wall and surface
  EXPECT_FALSE(cast({0, 0, -2}, -Eigen::Vector3f::UnitX()).hit);  // away from the wall
}

TEST_F(SceneTest, TMaxShorterThanWallMisses) {
  EXPECT_FALSE(cast({0, 0, -2}, Eigen::Vector3f::UnitX(), 9.9f).hit);
  EXPECT_TRUE(cast({0, 0, -2}, Eigen::Vector3f::UnitX(), 10.1f).hit);
}

TEST_F(SceneTest, WaterSurfaceIsLastMaterial) {
  const RayHit hit = cast({0, 0, -2}, Eigen::Vector3f::UnitZ());
  ASSERT_TRUE(hit.hit);
  EXPECT_NEAR(hit.distance_m, 2.0f, kToleranceM);
  EXPECT_TRUE(hit.water_surface);
  EXPECT_TRUE(hit.normal.isApprox(-Eigen::Vector3f::UnitZ(), 1e-6f));
  ASSERT_EQ(scene_.materials().size(), 3u);
  EXPECT_EQ(hit.material_id, 2u);
  EXPECT_EQ(scene_.materials().back().name, "surface");
  EXPECT_EQ(scene_.materials()[0].name, "wall");
}

TEST_F(SceneTest, SurfaceEndsAtMargin) {
  // The mesh spans x in [-10, 10]; the surface reaches 10 + 5 m.
  EXPECT_TRUE(cast({14.5f, 0, -2}, Eigen::Vector3f::UnitZ()).water_surface);
  EXPECT_FALSE(cast({15.5f, 0, -2}, Eigen::Vector3f::UnitZ()).hit);
  EXPECT_FALSE(cast({0, -15.5f, -2}, Eigen::Vector3f::UnitZ()).hit);
}

TEST_F(SceneTest, BoundsAreTheMeshOnly) {
  EXPECT_TRUE(scene_.bounds().min().isApprox(Eigen::Vector3f(-10, -10, -6)));
  EXPECT_TRUE(scene_.bounds().max().isApprox(Eigen::Vector3f(10, 10, -0.5f)));
}

TEST_F(SceneTest, BulkEqualsSingle) {
  const std::vector<Ray> rays = random_rays(10'003, 7);  // 10,003 = 1250 packets of 8 + 3
  std::vector<RayHit> hits;
  scene_.intersect(rays, hits);
  ASSERT_EQ(hits.size(), rays.size());
  std::size_t hit_count = 0;
  for (std::size_t i = 0; i < rays.size(); ++i) {
    expect_same(hits[i], scene_.intersect(rays[i]), i);
    hit_count += hits[i].hit ? 1 : 0;
  }
  EXPECT_GT(hit_count, rays.size() / 4);  // the rays exercise hits and misses alike
  EXPECT_LT(hit_count, rays.size());
}

TEST_F(SceneTest, BulkHandlesShortAndEmptyInput) {
  const std::vector<Ray> rays = random_rays(5, 11);
  std::vector<RayHit> hits(17);
  scene_.intersect(rays, hits);
  ASSERT_EQ(hits.size(), 5u);
  for (std::size_t i = 0; i < rays.size(); ++i) expect_same(hits[i], scene_.intersect(rays[i]), i);
  scene_.intersect(std::vector<Ray>{}, hits);
  EXPECT_TRUE(hits.empty());
}

TEST_F(SceneTest, ConcurrentQueriesAgree) {
  const std::vector<Ray> rays = random_rays(20'000, 3);
  std::vector<RayHit> expected(rays.size());
  for (std::size_t i = 0; i < rays.size(); ++i) expected[i] = scene_.intersect(rays[i]);

  std::vector<RayHit> single(rays.size()), bulk;
  std::thread single_thread([&] {
    for (std::size_t i = 0; i < rays.size(); ++i) single[i] = scene_.intersect(rays[i]);
  });
  std::thread bulk_thread([&] { scene_.intersect(rays, bulk); });
  single_thread.join();
  bulk_thread.join();
  ASSERT_EQ(bulk.size(), rays.size());
  for (std::size_t i = 0; i < rays.size(); ++i) {
    expect_same(single[i], expected[i], i);
    expect_same(bulk[i], expected[i], i);
  }
}

TEST(SceneInvalidMesh, Throws) {
  TriangleMesh empty;
  EXPECT_THROW(Scene(empty, Material{}), std::invalid_argument);
  TriangleMesh bad_index = wall_and_floor();
  bad_index.triangles[0] = {0, 1, 8};
  EXPECT_THROW(Scene(bad_index, Material{}), std::invalid_argument);
  TriangleMesh bad_material = wall_and_floor();
  bad_material.material_ids[0] = 2;
  EXPECT_THROW(Scene(bad_material, Material{}), std::invalid_argument);
}

}  // namespace
}  // namespace msislab::sim
