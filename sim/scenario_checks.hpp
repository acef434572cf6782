// Checks of a scenario against its scene before anything is simulated: the written path stays in
// the water, clear of the mesh and above the floor, and the named segments lie within the run.
// Geometry only; io/ turns each finding into one line at the scenario's line that set it
// (docs/scenes.md, "Scenario checks").
#pragma once

#include <cstddef>
#include <string>
#include <vector>

#include "geometry/time_segment.hpp"
#include "sim/scenario.hpp"
#include "sim/scene.hpp"

namespace msislab::sim {

struct ScenarioCheckConfig {
  double wall_clearance_m = 1.0;    ///< a leg passing closer to a surface: warning (about the
                                    ///< half-length of a small AUV such as Ictineu, 1.7 m long)
  double bottom_clearance_m = 0.5;  ///< an altitude under this: warning
  double step_m = 0.25;             ///< spacing of the points checked along each leg
  int directions = 16;              ///< horizontal rays per point for the wall clearance
};

/// The scenario key a finding is about.
enum class ScenarioKey {
  kWaypoint,  ///< vehicle.path[index]
  kDepth,     ///< vehicle.depth_m
  kSegment,   ///< segments[index]
};

struct ScenarioFinding {
  ScenarioKey key = ScenarioKey::kWaypoint;
  std::size_t index = 0;  ///< waypoint or segment, 0-based
  bool error = false;     ///< false: a warning (the run is still meaningful, the user may mean it)
  std::string what;       ///< what is wrong, in words and scene coordinates
  std::string name;       ///< a warning's name (kScenarioWarnings), which quiet_warnings silences
};

/// The names of the warnings a scenario's `quiet_warnings` may silence: a leg through an object,
/// a leg near a wall, an altitude under the clearance, a segment mostly after the run's end, and
/// a floor about as bright as the walls (settings/scenario_scene).
inline const std::vector<std::string> kScenarioWarnings = {
    "through_object", "wall_clearance", "bottom_clearance", "segment_after_run", "bright_floor"};

/// The written legs at the vehicle's depth against the scene. Errors: a point with no floor under
/// it (the path leaves the water; named as the face crossed when it lies beyond one), a point
/// under a face of the mesh (depth below the floor, or inside a sunken solid). Warnings: a leg
/// that runs through an object standing in the water and out again (a real track replayed
/// through a traced scene may clip a traced object; the simulator has no collisions), a leg
/// within wall_clearance_m of a steep face, an altitude under bottom_clearance_m. Each leg
/// reports its first error only. The vehicle cuts corners (pure pursuit, about the lookahead):
/// those arcs are not checked.
std::vector<ScenarioFinding> check_path(const VehicleConfig& vehicle, const Scene& scene,
                                        const ScenarioCheckConfig& config = {});

/// Segments against the run's duration (s): one that begins at or after the end scores nothing
/// (error); one that ends after it by more than half its length scores less than half of what it
/// names (warning). An end a little past the run is the usual way of writing "to the end".
std::vector<ScenarioFinding> check_segments(const std::vector<TimeSegment>& segments,
                                            double duration_s);

/// check_path, then check_segments against the duration of follow_path(scenario.vehicle).
std::vector<ScenarioFinding> check_scenario(const Scenario& scenario, const Scene& scene,
                                            const ScenarioCheckConfig& config = {});

}  // namespace msislab::sim
