#include "settings/scenario_scene.hpp"

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <set>

#include "io/input_error.hpp"
#include "io/mesh_io.hpp"
#include "io/yaml_fields.hpp"
#include "settings/scenario_yaml.hpp"
#include "sim/scenario_checks.hpp"
#include "sim/scene.hpp"
#include "sim/scene_materials.hpp"
#include "sim/thread_pool.hpp"

namespace msislab::settings {
namespace {

namespace fs = std::filesystem;

/// The scenario's keys with their lines (the file, already read once, is read again: it is small).
class ScenarioLines {
 public:
  explicit ScenarioLines(const std::string& path)
      : root_(io::load_yaml_file(path), path, ""),
        scene_(root_.map("scene")),
        vehicle_(root_.map("vehicle")),
        segments_(root_.map("segments")) {}

  io::YamlMap& root() { return root_; }
  io::YamlMap& scene() { return scene_; }

  [[noreturn]] void fail(const sim::ScenarioFinding& f, const sim::Scenario& s) {
    const Where w = where(f, s);
    w.map->fail_node(w.node, w.key, f.what);
  }

  std::string warning(const sim::ScenarioFinding& f, const sim::Scenario& s) {
    const Where w = where(f, s);
    return warning(*w.map, w.node, w.key, f.what);
  }

  static std::string warning(const io::YamlMap& map, const YAML::Node& at, const std::string& key,
                             const std::string& what) {
    return map.location(at, key) + ": warning: key '" + map.path_of(key) + "': " + what;
  }

 private:
  struct Where {
    io::YamlMap* map;
    YAML::Node node;  ///< empty: the key's line
    std::string key;
  };

  YAML::Node waypoint(std::size_t i) {
    const YAML::Node path = vehicle_.node("path");
    return path[i];
  }

  Where where(const sim::ScenarioFinding& f, const sim::Scenario& s) {
    switch (f.key) {
      case sim::ScenarioKey::kWaypoint:
        return {&vehicle_, waypoint(f.index), "path"};
      case sim::ScenarioKey::kDepth:
        return {&vehicle_, YAML::Node(), "depth_m"};
      case sim::ScenarioKey::kSegment:
        break;
    }
    return {&segments_, YAML::Node(), s.segments[f.index].name};
  }

  io::YamlMap root_, scene_, vehicle_, segments_;
};

/// A mesh path that names no file is the scenario's mistake: its line, and where it led.
void check_mesh_file(const sim::SceneConfig& scene, ScenarioLines& lines) {
  std::error_code error;
  if (fs::is_regular_file(scene.mesh_path, error)) return;
  std::string given;
  lines.scene().text("mesh", given);
  const std::string resolved = fs::absolute(scene.mesh_path, error).lexically_normal().string();
  lines.scene().fail("mesh", "'" + given + "' (relative to the scenario's folder) is " + resolved +
                                 (fs::exists(resolved, error) ? ", which is not a file"
                                                              : ", which does not exist"));
}

/// Whether the scenario's quiet_warnings silences the warning `name`.
bool quiet(const sim::Scenario& scenario, const std::string& name) {
  return std::find(scenario.quiet_warnings.begin(), scenario.quiet_warnings.end(), name) !=
         scenario.quiet_warnings.end();
}

/// The warning for a floor that returns about as much as the walls, or "" when it does not.
std::string bright_floor_warning(const sim::TriangleMesh& mesh, const std::vector<bool>& is_bottom,
                                 ScenarioLines& lines) {
  const sim::SurfaceBrightness b = sim::surface_brightness(mesh, is_bottom);
  if (!sim::bottom_as_bright_as_walls(b)) return "";
  char what[256];
  std::snprintf(what, sizeof what,
                "the floor's backscatter (%.3g, area-weighted) is within %.0f dB of the walls' "
                "(%.3g): the sonar will see mostly the floor around the vehicle. A mud floor is "
                "about 22 dB darker than a concrete wall (backscatter 0.003 against 0.5, "
                "docs/scenes.md)",
                b.bottom_backscatter, sim::kMinBottomContrast_dB, b.walls_backscatter);
  return ScenarioLines::warning(lines.root(), YAML::Node(), "scene", what);
}

sim::TriangleMesh read_mesh_with_defaults(const sim::SceneConfig& scene,
                                          std::vector<bool>& is_bottom) {
  sim::TriangleMesh mesh = io::read_mesh(
      scene.mesh_path, io::MeshMaterials{scene.default_material, scene.group_materials});
  std::set<std::string> explicit_groups;
  for (const auto& [name, material] : scene.group_materials) explicit_groups.insert(name);
  is_bottom = sim::bottom_faces(mesh);
  sim::assign_bottom_material(mesh, is_bottom, explicit_groups, scene.bottom_material);
  return mesh;
}

}  // namespace

sim::TriangleMesh read_scene_mesh(const sim::SceneConfig& scene) {
  std::vector<bool> is_bottom;
  return read_mesh_with_defaults(scene, is_bottom);
}

CheckedScenario read_checked_scenario(const std::string& path) {
  CheckedScenario out;
  out.scenario = read_scenario(path);
  ScenarioLines lines(path);
  check_mesh_file(out.scenario.scene, lines);
  sim::ThreadPoolScope pool;  // Embree's builds below start TBB workers: none may outlive this
  std::vector<bool> is_bottom;
  out.mesh = read_mesh_with_defaults(out.scenario.scene, is_bottom);
  {
    std::unique_ptr<sim::Scene> scene;
    try {
      scene = std::make_unique<sim::Scene>(out.mesh, out.scenario.scene.surface);
    } catch (const std::exception& e) {
      io::fail_file(out.scenario.scene.mesh_path,
                    std::string("cannot build the scene: ") + e.what());
    }
    for (const sim::ScenarioFinding& f : sim::check_scenario(out.scenario, *scene)) {
      if (f.error) lines.fail(f, out.scenario);
      if (!quiet(out.scenario, f.name)) out.warnings.push_back(lines.warning(f, out.scenario));
    }
  }
  // Only about what the author left to the defaults: a floor material given is meant.
  if (!lines.scene().has("bottom") && !quiet(out.scenario, "bright_floor")) {
    const std::string floor = bright_floor_warning(out.mesh, is_bottom, lines);
    if (!floor.empty()) out.warnings.push_back(floor);
  }
  pool.finish();
  return out;
}

}  // namespace msislab::settings
