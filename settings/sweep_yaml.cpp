#include "settings/sweep_yaml.hpp"

#include <filesystem>

#include "io/input_error.hpp"
#include "io/text_lines.hpp"
#include "io/yaml_fields.hpp"
#include "settings/config_yaml.hpp"
#include "settings/scenario_yaml.hpp"

namespace msislab::settings {

namespace fs = std::filesystem;

namespace {

const std::string kScenarioPrefix = "scenario.";
const std::string kSlamPrefix = "slam.";

bool starts_with(const std::string& s, const std::string& prefix) {
  return s.rfind(prefix, 0) == 0;
}

std::string flow_text(const YAML::Node& node) {
  YAML::Emitter out;
  out.SetMapFormat(YAML::Flow);
  out.SetSeqFormat(YAML::Flow);
  out << node;
  return out.c_str();
}

SweepValue value_of(const YAML::Node& node) {
  SweepValue v;
  v.text = flow_text(node);
  double number = 0.0;
  if (node.IsScalar() && io::parse_finite_scalar(node.Scalar(), number)) v.number = number;
  return v;
}

void check_key(io::YamlMap& map, const std::string& key) {
  const std::string rest = starts_with(key, kScenarioPrefix) ? key.substr(kScenarioPrefix.size())
                           : starts_with(key, kSlamPrefix)   ? key.substr(kSlamPrefix.size())
                                                             : std::string();
  if (rest.empty() || rest.front() == '.' || rest.back() == '.' ||
      rest.find("..") != std::string::npos) {
    map.fail(key, "is not a swept key: expected scenario.<key path> or slam.<key path>");
  }
}

/// Sets the value at a dotted key path in a mapping node, making the mappings on the way.
void set_path(YAML::Node root, const std::string& dotted, const std::string& value_text) {
  std::vector<std::string> parts;
  std::size_t start = 0;
  for (std::size_t dot; (dot = dotted.find('.', start)) != std::string::npos; start = dot + 1) {
    parts.push_back(dotted.substr(start, dot - start));
  }
  parts.push_back(dotted.substr(start));
  std::vector<YAML::Node> chain = {root};
  for (std::size_t i = 0; i + 1 < parts.size(); ++i) {
    YAML::Node next = chain.back()[parts[i]];
    if (!next.IsMap()) next = YAML::Node(YAML::NodeType::Map);
    chain.back()[parts[i]] = next;
    chain.push_back(next);
  }
  chain.back()[parts.back()] = YAML::Load(value_text);
}

std::string emit(const YAML::Node& node) {
  YAML::Emitter out;
  out << node;
  return std::string(out.c_str()) + "\n";
}

/// The methods list, when given, replaces the default methods.
void read_methods(io::YamlMap& root, Sweep& sweep) {
  if (!root.has("methods")) return;
  const YAML::Node methods = root.node("methods");
  if (!methods.IsSequence() || methods.size() == 0) {
    root.fail("methods", "expected a non-empty list of method names");
  }
  sweep.methods.clear();
  for (const YAML::Node& m : methods) {
    if (!m.IsScalar()) root.fail_node(m, "methods", "expected a method name");
    sweep.methods.push_back(m.Scalar());
  }
}

/// grid: a list of values per key; the cells are every combination, the last key fastest.
void read_grid(io::YamlMap& root, Sweep& sweep) {
  io::YamlMap grid = root.map("grid");
  std::vector<std::vector<SweepValue>> values;
  for (const std::string& key : grid.keys()) {
    check_key(grid, key);
    const YAML::Node list = grid.node(key);
    if (!list.IsSequence() || list.size() == 0) {
      grid.fail(key, "expected a non-empty list of values");
    }
    sweep.keys.push_back(key);
    values.emplace_back();
    for (const YAML::Node& v : list) values.back().push_back(value_of(v));
  }
  if (sweep.keys.empty()) root.fail("grid", "has no key");
  grid.finish();
  // Every combination, the last key fastest.
  std::vector<std::size_t> at(values.size(), 0);
  while (true) {
    SweepCell cell;
    for (std::size_t k = 0; k < values.size(); ++k) {
      cell.overrides.emplace_back(sweep.keys[k], values[k][at[k]]);
    }
    sweep.cells.push_back(std::move(cell));
    std::size_t k = values.size();
    while (k > 0 && ++at[k - 1] == values[k - 1].size()) at[--k] = 0;
    if (k == 0) break;
  }
}

/// cells: a list of mappings of key: value, one per cell; the keys in order of first appearance.
void read_cells(io::YamlMap& root, const std::string& path, Sweep& sweep) {
  const YAML::Node cells = root.node("cells");
  if (!cells.IsSequence() || cells.size() == 0) {
    root.fail("cells", "expected a non-empty list of cells (mappings of key: value)");
  }
  for (std::size_t i = 0; i < cells.size(); ++i) {
    io::YamlMap cell_map(cells[i], path, "cells[" + std::to_string(i) + "]");
    SweepCell cell;
    for (const std::string& key : cell_map.keys()) {
      check_key(cell_map, key);
      cell.overrides.emplace_back(key, value_of(cell_map.node(key)));
      if (std::find(sweep.keys.begin(), sweep.keys.end(), key) == sweep.keys.end()) {
        sweep.keys.push_back(key);
      }
    }
    if (cell.overrides.empty()) root.fail_node(cells[i], "cells", "a cell sets no key");
    cell_map.finish();
    sweep.cells.push_back(std::move(cell));
  }
}

/// InputError naming the first two cells that are the same.
void check_cells_differ(const std::string& path, const std::vector<SweepCell>& cells) {
  for (std::size_t i = 0; i < cells.size(); ++i) {
    for (std::size_t j = 0; j < i; ++j) {
      if (describe_cell(cells[i]) == describe_cell(cells[j])) {
        io::fail_file(path, "cells " + std::to_string(j) + " and " + std::to_string(i) +
                                " are the same (" + describe_cell(cells[i]) + ")");
      }
    }
  }
}

}  // namespace

Sweep read_sweep(const std::string& path) {
  io::YamlMap root(io::load_yaml_file(path), path, "");
  Sweep sweep;
  sweep.path = path;
  const fs::path dir = fs::path(path).parent_path();
  std::string scenario;
  if (!root.text("scenario", scenario)) root.fail("scenario", "is required");
  sweep.scenario_path = (dir / scenario).lexically_normal().string();
  std::string config;
  if (root.text("config", config)) sweep.config_path = (dir / config).lexically_normal().string();
  long long runs = 0;
  if (!root.integer("runs", runs)) root.fail("runs", "is required");
  if (runs < 1) root.fail("runs", "must be at least 1");
  sweep.runs = static_cast<int>(runs);
  read_methods(root, sweep);
  if (root.has("grid") == root.has("cells")) {
    root.fail(root.has("grid") ? "cells" : "grid", "give exactly one of grid and cells");
  }
  if (root.has("grid")) {
    read_grid(root, sweep);
  } else {
    read_cells(root, path, sweep);
  }
  root.finish();
  check_cells_differ(path, sweep.cells);
  return sweep;
}

std::string describe_cell(const SweepCell& cell) {
  std::string text;
  for (const auto& [key, value] : cell.overrides) {
    text += (text.empty() ? "" : ", ") + key + "=" + value.text;
  }
  return text;
}

CellInputs cell_inputs(const Sweep& sweep, std::size_t index) {
  const SweepCell& cell = sweep.cells.at(index);
  const std::string name =
      sweep.path + ", cell " + std::to_string(index) + " (" + describe_cell(cell) + ")";
  // The scenario: the files it names (its mesh, its heading history) absolute, then the
  // overrides.
  YAML::Node scenario = io::load_yaml_file(sweep.scenario_path);
  if (!scenario.IsMap()) io::fail_file(sweep.scenario_path, "expected a mapping of keys");
  const fs::path scenario_dir = fs::path(sweep.scenario_path).parent_path();
  for (const auto& [section, key] :
       {std::pair{"scene", "mesh"}, std::pair{"vehicle", "heading_csv"}}) {
    if (scenario[section] && scenario[section][key] && scenario[section][key].IsScalar()) {
      scenario[section][key] =
          fs::absolute(scenario_dir / scenario[section][key].Scalar()).lexically_normal().string();
    }
  }
  YAML::Node config = sweep.config_path.empty() ? YAML::Node(YAML::NodeType::Map)
                                                : io::load_yaml_file(sweep.config_path);
  if (config.IsNull()) config = YAML::Node(YAML::NodeType::Map);
  if (!config.IsMap()) io::fail_file(sweep.config_path, "expected a mapping of keys");
  for (const auto& [key, value] : cell.overrides) {
    if (starts_with(key, kScenarioPrefix)) {
      set_path(scenario, key.substr(kScenarioPrefix.size()), value.text);
    } else {
      set_path(config, key.substr(kSlamPrefix.size()), value.text);
    }
  }
  CellInputs inputs{emit(scenario), config.size() == 0 ? std::string() : emit(config)};
  read_scenario_text(inputs.scenario_text, name + " scenario", scenario_dir.string());
  if (!inputs.config_text.empty()) read_slam_config_text(inputs.config_text, name + " SLAM config");
  return inputs;
}

}  // namespace msislab::settings
