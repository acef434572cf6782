// Scenario files (YAML): parsed once, strictly, into sim::Scenario. Unknown keys, missing required
// keys (seed, scene.mesh, vehicle.depth_m, vehicle.speed_mps, vehicle.path), wrong types and bad
// values fail with "FILE:LINE: key 'a.b': what". Paths are relative to the scenario file.
#pragma once

#include <string>

#include "sim/scenario.hpp"

namespace msislab::settings {

sim::Scenario read_scenario(const std::string& path);
/// The same from a scenario's text; `name` stands for the file in errors, and relative paths are
/// relative to `dir`.
sim::Scenario read_scenario_text(const std::string& text, const std::string& name,
                                 const std::string& dir);

}  // namespace msislab::settings
