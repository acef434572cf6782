// A scenario with its scene, read and checked: what `msislab simulate` and `msislab montecarlo`
// start from (docs/scenes.md, "Materials" and "Scenario checks").
#pragma once

#include <string>
#include <vector>

#include "sim/mesh.hpp"
#include "sim/scenario.hpp"

namespace msislab::settings {

/// A scenario's mesh with its materials: each group named in scene.groups gets its material; the
/// faces of the other groups get scene.bottom where sim::bottom_faces finds the floor, and the
/// scene's default material elsewhere.
sim::TriangleMesh read_scene_mesh(const sim::SceneConfig& scene);

struct CheckedScenario {
  sim::Scenario scenario;
  sim::TriangleMesh mesh;             ///< with its materials (read_scene_mesh)
  std::vector<std::string> warnings;  ///< "FILE:LINE: warning: key 'a.b': what", one line each
};

/// read_scenario, the mesh (a mesh path that names no file fails at the scenario's `scene.mesh`
/// line, with the path it resolved to), then the checks of sim/scenario_checks and a floor as
/// bright as the walls. Errors throw InputError "FILE:LINE: key 'a.b': what" at the line of the
/// waypoint, key or segment concerned; warnings are returned. No worker thread is left running,
/// so the caller may fork() afterwards (sim/thread_pool).
CheckedScenario read_checked_scenario(const std::string& path);

}  // namespace msislab::settings
