#include "settings/external_config.hpp"

#include <yaml-cpp/yaml.h>

#include <utility>
#include <vector>

#include "geometry/angles.hpp"
#include "io/atomic_file.hpp"
#include "io/text_lines.hpp"
#include "io/yaml_fields.hpp"

namespace msislab::settings {

namespace {

/// Every dead_reckoning key of a SLAM config with its value in the file's units, as
/// read_slam_config() reads them (settings/config_yaml.cpp).
std::vector<std::pair<const char*, double>> dead_reckoning_keys(const DeadReckoningConfig& c) {
  return {{"dvl_sigma_mps", c.dvl_sigma_mps},
          {"heading_sigma_deg", c.heading_sigma_rad / kDegToRad},
          {"accel_sigma_mps2", c.accel_sigma_mps2},
          {"yaw_accel_sigma_radps2", c.yaw_accel_sigma_radps2},
          {"initial_velocity_sigma_mps", c.initial_velocity_sigma_mps},
          {"initial_yaw_rate_sigma_radps", c.initial_yaw_rate_sigma_radps},
          {"dvl_gate_chi2", c.dvl_gate_chi2},
          {"heading_bias_walk_deg_per_sqrt_s", c.heading_bias_walk_deg_per_sqrt_s},
          {"heading_bias_sigma_deg", c.heading_bias_sigma_deg},
          {"dvl_scale_sigma", c.dvl_scale_sigma}};
}

}  // namespace

void write_dead_reckoning_config(const std::string& path, const DeadReckoningConfig& config) {
  io::write_file_atomically(path, [&](std::ostream& out) {
    out << "# msislab SLAM config: the dead-reckoning noise (every other key at its default)\n"
        << "dead_reckoning:\n";
    for (const auto& [key, value] : dead_reckoning_keys(config)) {
      out << "  " << key << ": " << io::format_number(value) << "\n";
    }
  });
}

void write_resolved_config(const std::string& path, const std::string& config_path,
                           const DeadReckoningConfig& resolved) {
  YAML::Node root = YAML::Clone(io::load_yaml_file(config_path));
  if (!root.IsMap()) root = YAML::Node(YAML::NodeType::Map);
  root["navigation_noise"] = "config";
  YAML::Node section = root["dead_reckoning"];
  if (!section.IsMap()) section = YAML::Node(YAML::NodeType::Map);
  for (const auto& [key, value] : dead_reckoning_keys(resolved)) {
    section[key] = io::format_number(value);
  }
  root["dead_reckoning"] = section;
  YAML::Emitter emitter;
  emitter << root;
  io::write_file_atomically(path, [&](std::ostream& out) {
    out << "# msislab SLAM config: " << config_path
        << " with the dead-reckoning noise this run resolved\n"
        << emitter.c_str() << "\n";
  });
}

}  // namespace msislab::settings
