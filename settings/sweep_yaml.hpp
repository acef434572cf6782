// Sweep files (`msislab sweep SWEEP.yaml`, docs/cli.md): a base scenario and SLAM config, runs and
// methods, and the cells: a grid (every combination of the values given per key) or a list of
// overrides of scenario keys (`scenario.a.b`) and SLAM config keys (`slam.a.b`). Read strictly;
// each cell's scenario and config are made as YAML text from the base files with its overrides
// set, and checked by the strict readers before anything runs.
#pragma once

#include <optional>
#include <string>
#include <utility>
#include <vector>

namespace msislab::settings {

/// One override's value: its YAML text (flow style, e.g. `0.5` or `[1, 2]`) and, for a number,
/// the number (the figures' x axis).
struct SweepValue {
  std::string text;
  std::optional<double> number;
  bool operator==(const SweepValue& o) const { return text == o.text; }
};

struct SweepCell {
  std::vector<std::pair<std::string, SweepValue>> overrides;  ///< in the order of Sweep::keys
};

struct Sweep {
  std::string path;           ///< the sweep file
  std::string scenario_path;  ///< relative to the sweep file's folder, resolved
  std::string config_path;    ///< the same; empty: the default SLAM config
  int runs = 0;
  std::vector<std::string> methods = {"robocentric", "worldcentric"};
  std::vector<std::string> keys;  ///< the swept keys, in the order the file gives them
  std::vector<SweepCell> cells;   ///< grid: the last key varies fastest
};

/// Reads and checks a sweep file (keys, types, non-empty grids, cells that set only swept keys).
/// Throws InputError "FILE:LINE: key 'a.b': what".
Sweep read_sweep(const std::string& path);

/// A cell's inputs as text: the base scenario (the files it names, its mesh and heading history,
/// made absolute, so the text works from any folder) and the base SLAM config (or an empty one)
/// with the cell's overrides set, each checked by the strict reader; an error names the sweep file
/// and the cell.
struct CellInputs {
  std::string scenario_text;
  std::string config_text;
};
CellInputs cell_inputs(const Sweep& sweep, std::size_t cell);

/// "scenario.sonar.revolution_s=20, slam.trajectory_slam.iekf_iterations=1".
std::string describe_cell(const SweepCell& cell);

}  // namespace msislab::settings
