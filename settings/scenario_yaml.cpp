#include "settings/scenario_yaml.hpp"

#include <algorithm>
#include <cmath>
#include <filesystem>

#include "io/heading_csv.hpp"
#include "io/input_error.hpp"
#include "settings/config_fields.hpp"
#include "sim/scenario_checks.hpp"

namespace msislab::settings {

namespace {

void read_fraction(io::YamlMap& map, const std::string& key, float& value) {
  double v = value;
  map.number(key, v);
  if (v < 0.0 || v > 1.0) map.fail(key, "must be in [0, 1]");
  value = static_cast<float>(v);
}

/// backscatter, specular and incidence_exponent of a material; the map's other keys stay.
void read_material_keys(io::YamlMap& map, sim::Material& material) {
  read_fraction(map, "backscatter", material.backscatter);
  read_fraction(map, "specular", material.specular);
  double exponent = material.incidence_exponent;
  map.number("incidence_exponent", exponent);
  if (exponent < 0.0 || exponent > 10.0) map.fail("incidence_exponent", "must be in [0, 10]");
  material.incidence_exponent = static_cast<float>(exponent);
}

void read_material(io::YamlMap map, sim::Material& material) {
  read_material_keys(map, material);
  map.finish();
}

void read_scene(io::YamlMap map, const std::string& scenario_dir, sim::SceneConfig& scene) {
  if (!map.has("mesh")) map.fail_required("mesh", "is required");
  std::string mesh;
  map.text("mesh", mesh);
  scene.mesh_path = (std::filesystem::path(scenario_dir) / mesh).lexically_normal().string();
  read_material_keys(map, scene.default_material);
  read_material(map.map("bottom"), scene.bottom_material);
  io::YamlMap groups = map.map("groups");
  for (const std::string& name : groups.keys()) {
    sim::Material material = scene.default_material;
    material.name = name;
    read_material(groups.map(name), material);
    scene.group_materials[name] = material;
  }
  groups.finish();
  read_material(map.map("surface"), scene.surface);
  map.finish();
}

void read_path(io::YamlMap& map, std::vector<Eigen::Vector2d>& path) {
  if (!map.has("path")) map.fail_required("path", "is required");
  const YAML::Node node = map.node("path");
  if (!node.IsSequence()) map.fail_node(node, "path", "expected a list of [x, y] waypoints");
  path.clear();
  for (const YAML::Node& item : node) {
    double x = 0.0, y = 0.0;
    if (!item.IsSequence() || item.size() != 2 || !item[0].IsScalar() || !item[1].IsScalar() ||
        !io::parse_finite_scalar(item[0].Scalar(), x) ||
        !io::parse_finite_scalar(item[1].Scalar(), y)) {
      map.fail_node(item, "path", "each waypoint must be [x, y] in metres");
    }
    path.emplace_back(x, y);
  }
  if (path.size() < 2) map.fail("path", "needs at least 2 waypoints");
  for (std::size_t i = 1; i < path.size(); ++i) {
    if ((path[i] - path[i - 1]).norm() == 0.0) map.fail("path", "repeats a waypoint");
  }
}

/// Optional leg_speeds_mps: one speed > 0 per leg, the whole path in under 30 days.
void read_leg_speeds(io::YamlMap& map, sim::VehicleConfig& v) {
  if (!map.numbers("leg_speeds_mps", v.leg_speeds_mps)) return;
  const std::size_t legs = v.path_m.size() - 1;
  if (v.leg_speeds_mps.size() != legs) {
    map.fail("leg_speeds_mps", "expected " + std::to_string(legs) + " speeds (one per leg), got " +
                                   std::to_string(v.leg_speeds_mps.size()));
  }
  double duration_s = 0.0;
  for (std::size_t i = 0; i < legs; ++i) {
    if (!(v.leg_speeds_mps[i] > 0.0)) {
      map.fail("leg_speeds_mps", "speed " + std::to_string(i + 1) + " must be > 0");
    }
    duration_s += (v.path_m[i + 1] - v.path_m[i]).norm() / v.leg_speeds_mps[i];
  }
  if (duration_s > 30.0 * 86400.0) {
    map.fail("leg_speeds_mps", "the path would take over 30 days at these speeds");
  }
}

void read_vehicle(io::YamlMap map, const std::string& scenario_dir, sim::VehicleConfig& v) {
  v.depth_m = map.required_number("depth_m");
  v.speed_mps = map.required_number("speed_mps");
  require_positive(map, "speed_mps", v.speed_mps);
  if (v.depth_m < 0.0) map.fail("depth_m", "must be >= 0 (metres below the surface)");
  read_path(map, v.path_m);
  double length_m = 0.0;
  for (std::size_t i = 1; i < v.path_m.size(); ++i)
    length_m += (v.path_m[i] - v.path_m[i - 1]).norm();
  if (length_m / v.speed_mps > 30.0 * 86400.0) {
    map.fail("speed_mps", "the path would take over 30 days at this speed");
  }
  read_leg_speeds(map, v);
  double turn_rate_deg_s = v.max_turn_rate_radps * 180.0 / M_PI;
  map.number("max_turn_rate_deg_s", turn_rate_deg_s);
  require_positive(map, "max_turn_rate_deg_s", turn_rate_deg_s);
  v.max_turn_rate_radps = turn_rate_deg_s * M_PI / 180.0;
  map.number("lookahead_m", v.lookahead_m);
  require_positive(map, "lookahead_m", v.lookahead_m);
  map.number("start_time_s", v.start_time_s);
  map.number("step_s", v.step_s);
  if (!(v.step_s > 0.0 && v.step_s <= 0.1)) map.fail("step_s", "must be in (0, 0.1]");
  if (std::string heading; map.text("heading_csv", heading)) {
    const std::filesystem::path file = std::filesystem::path(scenario_dir) / heading;
    if (!std::filesystem::is_regular_file(file)) {
      map.fail("heading_csv", "no file " + file.lexically_normal().string());
    }
    v.heading_deg = io::read_heading_csv(file.lexically_normal().string());
  }
  map.finish();
}

/// Which way the head turns and over what: `rotation` (decreasing or increasing transducer
/// angle) and `sector_deg: [first, last]`, transducer angles rounded to the nearest step.
void read_sonar_scan(io::YamlMap& map, sim::SonarConfig& s) {
  if (std::string rotation; map.text("rotation", rotation)) {
    if (rotation == "decreasing") {
      s.rotation = sim::SonarRotation::kDecreasing;
    } else if (rotation == "increasing") {
      s.rotation = sim::SonarRotation::kIncreasing;
    } else {
      map.fail("rotation", "must be 'decreasing' or 'increasing', got '" + rotation + "'");
    }
  }
  std::vector<double> sector_deg;
  if (!map.numbers("sector_deg", sector_deg)) return;
  if (sector_deg.size() != 2) map.fail("sector_deg", "expected [first_deg, last_deg]");
  const double step_deg = 360.0 / s.steps_per_revolution;
  const auto index_of = [&](double deg) {
    const long i = std::lround(deg / step_deg) % s.steps_per_revolution;
    return static_cast<int>(i < 0 ? i + s.steps_per_revolution : i);
  };
  const sim::SonarSector sector{index_of(sector_deg[0]), index_of(sector_deg[1])};
  if (sector.first_index == sector.last_index) {
    map.fail("sector_deg", "its two ends fall on the same step; for whole turns leave it out");
  }
  s.sector = sector;
}

/// The sonar's geometry and timing: counts, widths, sound speeds, when it stops.
void read_sonar_geometry(io::YamlMap& map, sim::SonarConfig& s) {
  read_count(map, "steps_per_revolution", s.steps_per_revolution, 4, 6400);
  read_count(map, "bins", s.bins, 1, 10000);
  read_count(map, "rays_horizontal", s.rays_horizontal, 1, 64);
  read_count(map, "rays_vertical", s.rays_vertical, 1, 256);
  read_count(map, "multipath_bounces", s.multipath_bounces, 0, 8);
  for (auto [key, value] : {std::pair<const char*, double*>{"revolution_s", &s.revolution_s},
                            {"bin_m", &s.bin_m},
                            {"horizontal_beamwidth_deg", &s.horizontal_beamwidth_deg},
                            {"vertical_beamwidth_deg", &s.vertical_beamwidth_deg},
                            {"sound_speed_mps", &s.sound_speed_mps}}) {
    map.number(key, *value);
    require_positive(map, key, *value);
  }
  if (double water_mps = 0.0; map.number("water_sound_speed_mps", water_mps)) {
    if (!(water_mps >= 1300.0 && water_mps <= 1700.0)) {
      map.fail("water_sound_speed_mps", "must be within [1300, 1700] m/s");
    }
    s.water_sound_speed_mps = water_mps;
  }
  if (double stop_s = 0.0; map.number("stop_s", stop_s)) {
    require_positive(map, "stop_s", stop_s);
    s.stop_s = stop_s;
  }
  read_sonar_scan(map, s);
}

/// The levels: tilt, absorption, gain, TVG, noise, display, speckle, blanking.
void read_sonar_levels(io::YamlMap& map, sim::SonarConfig& s) {
  map.number("tilt_deg", s.tilt_deg);
  map.number("absorption_db_per_m", s.absorption_db_per_m);
  if (s.absorption_db_per_m < 0.0) map.fail("absorption_db_per_m", "must be >= 0");
  map.number("gain_db", s.gain_db);
  map.number("tvg_db_per_decade", s.tvg_db_per_decade);
  map.number("noise_level_db", s.noise_level_db);
  map.number("display_min_db", s.display_min_db);
  map.number("display_max_db", s.display_max_db);
  if (!(s.display_max_db > s.display_min_db)) {
    map.fail("display_max_db", "must be above display_min_db");
  }
  map.boolean("speckle", s.speckle);
  read_count(map, "speckle_looks", s.speckle_looks, 1, 64);
  map.number("min_range_m", s.min_range_m);
}

/// The echo's shape: the beam pattern, the traced span, the footprint, pulse and receiver.
void read_sonar_echo(io::YamlMap& map, sim::SonarConfig& s) {
  std::string pattern = s.beam_pattern == sim::BeamPattern::kSinc ? "sinc" : "gaussian";
  map.text("beam_pattern", pattern);
  if (pattern != "gaussian" && pattern != "sinc") {
    map.fail("beam_pattern", "must be gaussian or sinc, not '" + pattern + "'");
  }
  s.beam_pattern = pattern == "sinc" ? sim::BeamPattern::kSinc : sim::BeamPattern::kGaussian;
  for (auto [key, value] : {std::pair<const char*, double*>{"horizontal_span_beamwidths",
                                                            &s.horizontal_span_beamwidths},
                            {"vertical_span_beamwidths", &s.vertical_span_beamwidths},
                            {"roughness_length_m", &s.roughness_length_m}}) {
    map.number(key, *value);
    require_positive(map, key, *value);
  }
  map.boolean("footprint", s.footprint);
  for (auto [key, value] : {std::pair<const char*, double*>{"pulse_length_us", &s.pulse_length_us},
                            {"receiver_time_constant_us", &s.receiver_time_constant_us},
                            {"roughness_db", &s.roughness_db}}) {
    map.number(key, *value);
    if (*value < 0.0) map.fail(key, "must be >= 0");
  }
  if (s.pulse_length_us > 10000.0 || s.receiver_time_constant_us > 10000.0) {
    map.fail(s.pulse_length_us > 10000.0 ? "pulse_length_us" : "receiver_time_constant_us",
             "must be at most 10000 (10 ms, 7.5 m of range)");
  }
}

void read_sonar(io::YamlMap map, sim::SonarConfig& s) {
  read_sonar_geometry(map, s);
  read_sonar_levels(map, s);
  read_sonar_echo(map, s);
  io::YamlMap mount = map.map("mount");
  read_sonar_mount(mount, s.mount);
  mount.finish();
  map.finish();
}

/// Reads a probability if present; fails naming the key unless it lies in [0, 1].
void read_probability(io::YamlMap& map, const std::string& key, double& value) {
  map.number(key, value);
  if (value < 0.0 || value > 1.0) map.fail(key, "must be in [0, 1]");
}

/// Reads a value if present; fails naming the key if it is negative.
void read_non_negative(io::YamlMap& map, const std::string& key, double& value) {
  map.number(key, value);
  if (value < 0.0) map.fail(key, "must be >= 0");
}

void read_dvl(io::YamlMap map, sim::DvlConfig& d) {
  map.number("rate_hz", d.rate_hz);
  require_positive(map, "rate_hz", d.rate_hz);
  read_non_negative(map, "noise_sigma_mps", d.noise_sigma_mps);
  read_probability(map, "outlier_probability", d.outlier_probability);
  read_non_negative(map, "outlier_sigma_mps", d.outlier_sigma_mps);
  std::vector<double> bias;
  if (map.numbers("bias_mps", bias)) {
    if (bias.size() != 2) map.fail("bias_mps", "expected [x, y] in the DVL frame");
    d.bias_mps = {bias[0], bias[1]};
  }
  map.number("scale_factor", d.scale_factor);
  if (!(d.scale_factor >= 0.5 && d.scale_factor <= 2.0)) {
    map.fail("scale_factor", "must be within [0.5, 2]");
  }
  read_probability(map, "dropout_probability", d.dropout_probability);
  read_probability(map, "degraded_dropout_probability", d.degraded_dropout_probability);
  map.number("degraded_fraction", d.degraded_fraction);
  if (d.degraded_fraction < 0.0 || d.degraded_fraction >= 1.0) {
    map.fail("degraded_fraction", "must be in [0, 1)");
  }
  map.number("degraded_duration_s", d.degraded_duration_s);
  require_positive(map, "degraded_duration_s", d.degraded_duration_s);
  map.number("max_altitude_m", d.max_altitude_m);
  require_positive(map, "max_altitude_m", d.max_altitude_m);
  io::YamlMap mount = map.map("mount");
  read_dvl_mount(mount, d.mount);
  mount.finish();
  map.finish();
}

void read_mru(io::YamlMap map, sim::MruConfig& m) {
  map.number("rate_hz", m.rate_hz);
  require_positive(map, "rate_hz", m.rate_hz);
  read_non_negative(map, "heading_noise_deg", m.heading_noise_deg);
  map.number("bias_initial_deg", m.bias_initial_deg);
  read_non_negative(map, "bias_random_walk_deg_per_sqrt_s", m.bias_random_walk_deg_per_sqrt_s);
  map.number("deviation_cos_deg", m.deviation_cos_deg);
  map.number("deviation_sin_deg", m.deviation_sin_deg);
  io::YamlMap mount = map.map("mount");
  read_mru_mount(mount, m.mount);
  mount.finish();
  map.finish();
}

void read_gps(io::YamlMap map, sim::GpsConfig& g) {
  map.boolean("enabled", g.enabled);
  map.number("rate_hz", g.rate_hz);
  require_positive(map, "rate_hz", g.rate_hz);
  read_non_negative(map, "noise_sigma_m", g.noise_sigma_m);
  read_non_negative(map, "correlated_sigma_m", g.correlated_sigma_m);
  map.number("correlation_time_s", g.correlation_time_s);
  require_positive(map, "correlation_time_s", g.correlation_time_s);
  read_non_negative(map, "tether_length_m", g.tether_length_m);
  read_local_frame(map, g.frame);
  map.finish();
}

void read_detections(io::YamlMap map, sim::DetectionModelConfig& d) {
  std::string window;
  if (map.text("smoothing_bins", window) && window == "auto") {
    d.smoothing_bins = 0;  // MATLAB's default window, per revolution
  } else {
    read_count(map, "smoothing_bins", d.smoothing_bins, 1, 999);
  }
  map.number("smoothing_factor", d.smoothing_factor);
  if (d.smoothing_factor < 0.0 || d.smoothing_factor > 1.0) {
    map.fail("smoothing_factor", "must be in [0, 1]");
  }
  map.number("ramp_max", d.ramp_max);
  map.number("threshold", d.threshold);
  map.number("min_range_m", d.min_range_m);
  if (d.min_range_m < 0.0) map.fail("min_range_m", "must be >= 0");
  map.finish();
}

}  // namespace

namespace {
sim::Scenario scenario_from_yaml(const YAML::Node& node, const std::string& path,
                                 const std::string& dir) {
  io::YamlMap root(node, path, "");
  sim::Scenario s;
  root.text("name", s.name);
  long long seed = 0;
  if (!root.integer("seed", seed)) root.fail_required("seed", "is required");
  if (seed < 0) root.fail("seed", "must be >= 0");
  s.seed = static_cast<std::uint64_t>(seed);
  if (!root.has("scene")) root.fail_required("scene", "is required (scene.mesh)");
  if (!root.has("vehicle")) root.fail_required("vehicle", "is required (depth_m, speed_mps, path)");
  read_scene(root.map("scene"), dir, s.scene);
  read_vehicle(root.map("vehicle"), dir, s.vehicle);
  s.segments = read_segments(root.map("segments"));
  read_sonar(root.map("sonar"), s.sonar);
  read_dvl(root.map("dvl"), s.dvl);
  read_mru(root.map("mru"), s.mru);
  read_gps(root.map("gps"), s.gps);
  read_detections(root.map("detections"), s.detections);
  if (root.texts("quiet_warnings", s.quiet_warnings)) {
    for (const std::string& name : s.quiet_warnings) {
      if (std::find(sim::kScenarioWarnings.begin(), sim::kScenarioWarnings.end(), name) !=
          sim::kScenarioWarnings.end()) {
        continue;
      }
      const std::string near = io::closest_key(name, sim::kScenarioWarnings);
      std::string known;
      for (const std::string& w : sim::kScenarioWarnings) known += (known.empty() ? "" : ", ") + w;
      root.fail("quiet_warnings", "unknown warning '" + name + "'" +
                                      (near.empty() ? "" : " (did you mean '" + near + "'?)") +
                                      "; known: " + known);
    }
  }
  if (root.has("stated_calibration")) {
    // What the dataset's calibration.yaml says: the sensors' own values, these keys changed.
    Calibration stated = sim::true_calibration(s);
    io::YamlMap stated_map = root.map("stated_calibration");
    read_calibration_sections(stated_map, stated);
    stated_map.finish();
    s.stated_calibration = stated;
  }
  root.finish();
  return s;
}
}  // namespace

sim::Scenario read_scenario(const std::string& path) {
  return scenario_from_yaml(io::load_yaml_file(path), path,
                            std::filesystem::path(path).parent_path().string());
}

sim::Scenario read_scenario_text(const std::string& text, const std::string& name,
                                 const std::string& dir) {
  return scenario_from_yaml(io::load_yaml_text(text, name), name, dir);
}

}  // namespace msislab::settings
