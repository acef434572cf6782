// navigation_noise.yaml (docs/formats.md): the navigation noise a simulated dataset was made with,
// in the SLAM config's dead_reckoning keys; and the config a run on a dataset uses, the config
// file's keys over that noise over the defaults.
#include <cmath>
#include <cstdio>

#include "io/atomic_file.hpp"
#include "io/text_lines.hpp"
#include "io/yaml_fields.hpp"
#include "settings/config_fields.hpp"
#include "settings/config_yaml.hpp"

namespace msislab::settings {

namespace {

struct NoiseKey {
  const char* name;
  double NavigationNoise::*value;
  bool white;  ///< a white-noise sigma: 0 leaves the filter's own (a filter needs one above 0)
  void (*set)(DeadReckoningConfig&, double);  ///< the dead reckoning's key (units: the file's)
};

constexpr NoiseKey kNoiseKeys[] = {
    {"dvl_sigma_mps", &NavigationNoise::dvl_sigma_mps, true,
     [](DeadReckoningConfig& c, double v) { c.dvl_sigma_mps = v; }},
    {"heading_sigma_deg", &NavigationNoise::heading_sigma_deg, true,
     [](DeadReckoningConfig& c, double v) { c.heading_sigma_rad = v * M_PI / 180.0; }},
    {"heading_bias_walk_deg_per_sqrt_s", &NavigationNoise::heading_bias_walk_deg_per_sqrt_s, false,
     [](DeadReckoningConfig& c, double v) { c.heading_bias_walk_deg_per_sqrt_s = v; }},
    {"heading_bias_sigma_deg", &NavigationNoise::heading_bias_sigma_deg, false,
     [](DeadReckoningConfig& c, double v) { c.heading_bias_sigma_deg = v; }},
    {"dvl_scale_sigma", &NavigationNoise::dvl_scale_sigma, false,
     [](DeadReckoningConfig& c, double v) { c.dvl_scale_sigma = v; }},
};

NavigationNoise navigation_noise_from_yaml(const YAML::Node& node, const std::string& name) {
  io::YamlMap root(node, name, "");
  io::YamlMap map = root.map("dead_reckoning");
  NavigationNoise noise;
  for (const NoiseKey& key : kNoiseKeys) {
    map.number(key.name, noise.*key.value);
    if (!(noise.*key.value >= 0.0)) map.fail(key.name, "must be >= 0");
  }
  if (noise.dvl_scale_sigma >= 0.5) map.fail("dvl_scale_sigma", "must be under 0.5");
  map.finish();
  root.finish();
  return noise;
}

std::string navigation_noise_yaml(const NavigationNoise& noise) {
  std::string text =
      "# The navigation noise of the scenario that made this dataset, in the SLAM config's\n"
      "# dead_reckoning keys (docs/formats.md). msislab run, montecarlo and sweep take each value\n"
      "# the config does not set.\n"
      "dead_reckoning:\n";
  for (const NoiseKey& key : kNoiseKeys) {
    text += std::string("  ") + key.name + ": " + io::format_number(noise.*key.value) + "\n";
  }
  return text;
}

std::string short_number(double value) {
  char text[32];
  std::snprintf(text, sizeof text, "%.4g", value);
  return text;
}

std::string noise_values(const NavigationNoise& noise) {
  std::string text;
  for (const NoiseKey& key : kNoiseKeys) {
    text += std::string(text.empty() ? "" : ", ") + key.name + " " + short_number(noise.*key.value);
  }
  return text;
}

}  // namespace

NavigationNoise read_navigation_noise(const std::string& path) {
  return navigation_noise_from_yaml(io::load_yaml_file(path), path);
}

void write_navigation_noise(const std::string& path, const NavigationNoise& noise) {
  const std::string text = navigation_noise_yaml(noise);
  io::write_text_atomically(path, text);
}

NavigationNoise navigation_noise_as_stored(const NavigationNoise& noise) {
  return navigation_noise_from_yaml(YAML::Load(navigation_noise_yaml(noise)),
                                    "navigation_noise.yaml");
}

DatasetConfig slam_config_for_dataset(const std::string& config_path,
                                      const std::optional<NavigationNoise>& noise,
                                      const std::string& noise_source) {
  const YAML::Node node = config_path.empty() ? YAML::Node() : io::load_yaml_file(config_path);
  const std::string name = config_path.empty() ? "(default config)" : config_path;
  // Read once as it is: whether it asks for the dataset's noise (and any error in it, first).
  const SlamConfig own = slam_config_of(node, name, SlamConfig{});
  DatasetConfig out;
  out.config = own;
  if (!noise) return out;
  if (!own.navigation_noise_from_dataset) {
    out.noise_note = noise_source + " states the sensors' noise (" + noise_values(*noise) +
                     "); `navigation_noise: dataset` in a config uses it";
    return out;
  }
  // Each key the file does not have (whatever its value there: the reader checks it) comes from
  // the dataset.
  const YAML::Node section =
      node.IsMap() && node["dead_reckoning"] ? node["dead_reckoning"] : YAML::Node();
  SlamConfig base;
  std::string taken;
  for (const NoiseKey& key : kNoiseKeys) {
    const double value = (*noise).*key.value;
    if ((section.IsMap() && section[key.name]) || (key.white && !(value > 0.0))) continue;
    key.set(base.dead_reckoning, value);
    taken += std::string(taken.empty() ? "" : ", ") + key.name + " " + short_number(value);
  }
  out.config = slam_config_of(node, name, base);
  if (!taken.empty()) {
    out.noise_note = "dead reckoning noise from " + noise_source + " (" + taken +
                     "), where the config does not set it";
  }
  return out;
}

}  // namespace msislab::settings
