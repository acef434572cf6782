// sim/scene_materials: the floor found by geometry in a mesh of one group (a basin with a pier, a
// sunken deck and a pier deck above the water), the default floor material given to it alone,
// and the floor-as-bright-as-the-walls test.
#include "sim/scene_materials.hpp"

#include <gtest/gtest.h>

#include "sim/scene_builder.hpp"

namespace msislab::sim {
namespace {

constexpr float kFloorZ_m = -4.0f;

/// The faces added by one call, [begin, end).
struct Faces {
  std::size_t begin = 0, end = 0;
};

/// A 60 x 30 m basin (floor at -4 m) with a pier (a closed box from the floor to +1 m), a sunken
/// deck (a plate at -2 m) and a deck above the water (a plate at +1 m), all in the group `group`.
struct OneGroupBasin {
  TriangleMesh mesh;
  Faces floor, walls, pier, sunken_deck, high_deck;

  explicit OneGroupBasin(const std::string& group = "") {
    MeshBuilder b;
    const auto g = b.group(group, 0.5f, 0.05f);
    const BasinOutline outline{{{0, 0}, {60, 0}, {60, 30}, {0, 30}}, {true, true, true, true}};
    add_basin(b, outline, {1.0, kFloorZ_m, 0.0}, g, g);
    // add_basin adds the walls (2 triangles per edge), then the floor.
    walls = {0, 8};
    floor = {8, b.mesh().triangles.size()};
    pier = add(b, [&] { add_prism(b, {{28, 20}, {32, 20}, {32, 29}, {28, 29}}, kFloorZ_m, 1, g); });
    sunken_deck = add(b, [&] { plate(b, -2.0, g, false); });
    high_deck = add(b, [&] { plate(b, 1.0, g, true); });
    mesh = b.mesh();
  }

  template <typename F>
  static Faces add(MeshBuilder& b, F&& f) {
    const std::size_t begin = b.mesh().triangles.size();
    f();
    return {begin, b.mesh().triangles.size()};
  }

  /// A 4 x 4 m horizontal plate at (10..14, 10..14); `up` chooses its winding.
  static void plate(MeshBuilder& b, double z_m, std::uint32_t g, bool up) {
    const int p0 = b.vertex({10, 10, z_m}), p1 = b.vertex({14, 10, z_m});
    const int p2 = b.vertex({14, 14, z_m}), p3 = b.vertex({10, 14, z_m});
    if (up) {
      b.quad(p0, p1, p2, p3, g);
    } else {
      b.quad(p0, p3, p2, p1, g);
    }
  }
};

void expect_all(const std::vector<bool>& is_bottom, Faces faces, bool value, const char* what) {
  for (std::size_t i = faces.begin; i < faces.end; ++i) {
    EXPECT_EQ(is_bottom[i], value) << what << ", triangle " << i;
  }
}

TEST(SceneMaterials, TheFloorIsFoundByItsShape) {
  const OneGroupBasin basin;
  const std::vector<bool> is_bottom = bottom_faces(basin.mesh);
  ASSERT_EQ(is_bottom.size(), basin.mesh.triangles.size());
  expect_all(is_bottom, basin.floor, true, "floor");
  expect_all(is_bottom, basin.walls, false, "wall");
  expect_all(is_bottom, basin.sunken_deck, false, "sunken deck (the floor is under it)");
  expect_all(is_bottom, basin.high_deck, false, "deck above the water");
  // The pier: its sides are steep, its top has the water surface under it; only its foot, which
  // lies on the floor and faces down, counts as floor (and is hidden by the floor anyway).
  int pier_floor = 0;
  for (std::size_t i = basin.pier.begin; i < basin.pier.end; ++i) {
    const Eigen::Vector3i& t = basin.mesh.triangles[i];
    const bool at_floor = basin.mesh.vertices_m[t[0]].z() == kFloorZ_m &&
                          basin.mesh.vertices_m[t[1]].z() == kFloorZ_m &&
                          basin.mesh.vertices_m[t[2]].z() == kFloorZ_m;
    EXPECT_EQ(is_bottom[i], at_floor) << "pier triangle " << i;
    pier_floor += at_floor ? 1 : 0;
  }
  EXPECT_GT(pier_floor, 0);
}

TEST(SceneMaterials, AFloorWoundTheWrongWayIsStillTheFloor) {
  OneGroupBasin basin;
  for (std::size_t i = basin.floor.begin; i < basin.floor.end; ++i) {
    std::swap(basin.mesh.triangles[i][1], basin.mesh.triangles[i][2]);
  }
  expect_all(bottom_faces(basin.mesh), basin.floor, true, "floor wound clockwise");
}

TEST(SceneMaterials, TheFloorOfAGroupWithoutAMaterialGetsTheBottomMaterial) {
  OneGroupBasin basin;
  const std::vector<bool> is_bottom = bottom_faces(basin.mesh);
  const Material mud{"", 0.003f, 0.3f};
  assign_bottom_material(basin.mesh, is_bottom, {}, mud);
  ASSERT_EQ(basin.mesh.materials.size(), 2u);
  EXPECT_EQ(basin.mesh.materials[1].name, "bottom");  // the unnamed group's floor
  EXPECT_EQ(basin.mesh.group_names[1], "");
  for (std::size_t i = 0; i < basin.mesh.triangles.size(); ++i) {
    const Material& m = basin.mesh.materials[basin.mesh.material_ids[i]];
    EXPECT_EQ(m.backscatter, is_bottom[i] ? 0.003f : 0.5f) << "triangle " << i;
    EXPECT_EQ(m.specular, is_bottom[i] ? 0.3f : 0.05f) << "triangle " << i;
  }

  OneGroupBasin named("basin");
  assign_bottom_material(named.mesh, bottom_faces(named.mesh), {}, mud);
  EXPECT_EQ(named.mesh.materials[1].name, "basin/bottom");
  EXPECT_EQ(named.mesh.group_names[1], "basin");
}

TEST(SceneMaterials, AGroupWithItsOwnMaterialKeepsItAndAnAllFloorGroupKeepsItsName) {
  MeshBuilder b;
  const auto walls = b.group("walls", 0.5f, 0.05f);
  const auto bottom = b.group("bottom", 0.5f, 0.05f);
  add_basin(b, {{{0, 0}, {10, 0}, {10, 10}, {0, 10}}, {true, true, true, true}}, {1, -3, 0}, walls,
            bottom);
  TriangleMesh mesh = b.mesh();
  const Material mud{"", 0.003f, 0.3f};
  TriangleMesh kept = mesh;
  assign_bottom_material(kept, bottom_faces(kept), {"bottom"}, mud);
  EXPECT_EQ(kept.materials.size(), 2u);
  EXPECT_EQ(kept.materials[bottom].backscatter, 0.5f) << "scene.groups.bottom given: kept";

  assign_bottom_material(mesh, bottom_faces(mesh), {}, mud);
  ASSERT_EQ(mesh.materials.size(), 2u) << "no face split off: the whole group is floor";
  EXPECT_EQ(mesh.materials[bottom].name, "bottom");
  EXPECT_EQ(mesh.materials[bottom].backscatter, 0.003f);
  EXPECT_EQ(mesh.materials[walls].backscatter, 0.5f);
}

TEST(SceneMaterials, AFloorWithin10DbOfTheWallsIsAsBrightAsThem) {
  OneGroupBasin basin;
  const std::vector<bool> is_bottom = bottom_faces(basin.mesh);
  const SurfaceBrightness same = surface_brightness(basin.mesh, is_bottom);
  EXPECT_NEAR(same.bottom_area_m2, 60.0 * 30.0 + 4.0 * 9.0, 1e-3);  // floor and the pier's foot
  EXPECT_FLOAT_EQ(static_cast<float>(same.bottom_backscatter), 0.5f);
  EXPECT_FLOAT_EQ(static_cast<float>(same.walls_backscatter), 0.5f);
  EXPECT_TRUE(bottom_as_bright_as_walls(same));

  assign_bottom_material(basin.mesh, is_bottom, {}, {"", 0.003f, 0.3f});
  const SurfaceBrightness mud = surface_brightness(basin.mesh, is_bottom);
  EXPECT_FLOAT_EQ(static_cast<float>(mud.bottom_backscatter), 0.003f);
  EXPECT_FALSE(bottom_as_bright_as_walls(mud));

  // 9 dB darker is still as bright; 11 dB is not.
  EXPECT_TRUE(bottom_as_bright_as_walls({0.5 * 0.126, 1.0, 0.5, 1.0}));
  EXPECT_FALSE(bottom_as_bright_as_walls({0.5 * 0.079, 1.0, 0.5, 1.0}));
  EXPECT_FALSE(bottom_as_bright_as_walls({0.5, 0.0, 0.5, 1.0})) << "no floor";
}

}  // namespace
}  // namespace msislab::sim
