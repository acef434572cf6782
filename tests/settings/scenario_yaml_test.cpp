// Scenario files: a minimal scenario gets every default of sim/scenario.hpp, each section's keys
// land in the struct, the mesh path is resolved against the scenario's folder, and every class of
// bad input fails with InputError "FILE:LINE: key 'a.b': ..." (docs/interfaces.md).
#include "settings/scenario_yaml.hpp"

#include <gtest/gtest.h>

#include <cctype>
#include <cmath>
#include <filesystem>
#include <string>

#include "geometry/angles.hpp"
#include "io/input_error.hpp"
#include "io/yaml_fields.hpp"
#include "test_support.hpp"

namespace msislab::settings {
namespace {

namespace fs = std::filesystem;
using testing::TempDir;
using testing::write_text;

constexpr double kScenarioAngleTolerance_rad = 1e-12;

// The required keys only; line numbers below refer to this layout.
constexpr const char* kMinimal =
    "seed: 7\n"                              // 1
    "scene:\n"                               // 2
    "  mesh: basin.obj\n"                    // 3
    "vehicle:\n"                             // 4
    "  depth_m: 1.5\n"                       // 5
    "  speed_mps: 0.5\n"                     // 6
    "  path: [[0, 0], [10, 0], [10, 5]]\n";  // 7

// The message of the InputError that read_scenario(path) throws ("" and a failure when none).
std::string error_of(const std::string& path) {
  try {
    read_scenario(path);
  } catch (const io::InputError& e) {
    return e.what();
  }
  ADD_FAILURE() << "no InputError for " << path;
  return "";
}

// Whether message starts "PATH:N: " with N a positive line number.
bool has_line_number(const std::string& message, const std::string& path) {
  if (message.rfind(path + ":", 0) != 0) return false;
  std::size_t i = path.size() + 1;
  const std::size_t digits_begin = i;
  while (i < message.size() && std::isdigit(static_cast<unsigned char>(message[i]))) ++i;
  return i > digits_begin && message.compare(i, 2, ": ") == 0 && message[digits_begin] != '0';
}

// Writes `text` as a scenario and expects InputError "PATH:LINE: ... key 'KEY' ... WHAT"; line 0
// accepts any line number (an absent key is reported at its enclosing mapping), key "" and what ""
// check nothing.
void expect_bad(const std::string& text, int line, const std::string& key,
                const std::string& what = "") {
  SCOPED_TRACE(text);
  const TempDir dir;
  const std::string path = write_text(dir.file("bad.yaml"), text);
  const std::string message = error_of(path);
  const std::string where =
      line > 0 ? path + ":" + std::to_string(line) + ":" : std::string(path + ":");
  EXPECT_EQ(message.rfind(where, 0), 0u) << message << "\nexpected to start with " << where;
  EXPECT_TRUE(has_line_number(message, path)) << message << "\nexpected " << path << ":LINE: ";
  if (!key.empty()) {
    EXPECT_NE(message.find("key '" + key + "'"), std::string::npos)
        << message << "\nexpected key '" << key << "'";
  }
  if (!what.empty()) {
    EXPECT_NE(message.find(what), std::string::npos) << message << "\nexpected '" << what << "'";
  }
}

// kMinimal with line `line` (1-based) replaced by `replacement` (which may hold several lines or
// none).
std::string minimal_with(int line, const std::string& replacement) {
  std::string text = kMinimal;
  std::size_t begin = 0;
  for (int i = 1; i < line; ++i) begin = text.find('\n', begin) + 1;
  const std::size_t end = text.find('\n', begin) + 1;
  return text.replace(begin, end - begin, replacement);
}

void expect_same_material(const sim::Material& a, const sim::Material& b) {
  EXPECT_EQ(a.name, b.name);
  EXPECT_EQ(a.backscatter, b.backscatter);
  EXPECT_EQ(a.specular, b.specular);
}

TEST(ScenarioYaml, MinimalScenarioKeepsEveryDefault) {
  const TempDir dir;
  const sim::Scenario s = read_scenario(write_text(dir.file("s.yaml"), kMinimal));
  const sim::Scenario d;  // the defaults of sim/scenario.hpp

  EXPECT_EQ(s.seed, 7u);
  EXPECT_EQ(s.name, d.name);
  EXPECT_EQ(s.scene.mesh_path, (dir.path() / "basin.obj").string());
  expect_same_material(s.scene.default_material, d.scene.default_material);
  expect_same_material(s.scene.bottom_material, d.scene.bottom_material);
  expect_same_material(s.scene.surface, d.scene.surface);
  EXPECT_TRUE(s.scene.group_materials.empty());

  EXPECT_EQ(s.vehicle.depth_m, 1.5);
  EXPECT_EQ(s.vehicle.speed_mps, 0.5);
  ASSERT_EQ(s.vehicle.path_m.size(), 3u);
  EXPECT_EQ(s.vehicle.path_m[0], Eigen::Vector2d(0.0, 0.0));
  EXPECT_EQ(s.vehicle.path_m[1], Eigen::Vector2d(10.0, 0.0));
  EXPECT_EQ(s.vehicle.path_m[2], Eigen::Vector2d(10.0, 5.0));
  EXPECT_NEAR(s.vehicle.max_turn_rate_radps, d.vehicle.max_turn_rate_radps, 1e-15);
  EXPECT_EQ(s.vehicle.lookahead_m, d.vehicle.lookahead_m);
  EXPECT_EQ(s.vehicle.start_time_s, d.vehicle.start_time_s);
  EXPECT_EQ(s.vehicle.step_s, d.vehicle.step_s);

  EXPECT_EQ(s.sonar.steps_per_revolution, d.sonar.steps_per_revolution);
  EXPECT_EQ(s.sonar.revolution_s, d.sonar.revolution_s);
  EXPECT_EQ(s.sonar.bins, d.sonar.bins);
  EXPECT_EQ(s.sonar.bin_m, d.sonar.bin_m);
  EXPECT_EQ(s.sonar.horizontal_beamwidth_deg, d.sonar.horizontal_beamwidth_deg);
  EXPECT_EQ(s.sonar.vertical_beamwidth_deg, d.sonar.vertical_beamwidth_deg);
  EXPECT_EQ(s.sonar.tilt_deg, d.sonar.tilt_deg);
  EXPECT_EQ(s.sonar.rays_horizontal, d.sonar.rays_horizontal);
  EXPECT_EQ(s.sonar.rays_vertical, d.sonar.rays_vertical);
  EXPECT_EQ(s.sonar.sound_speed_mps, d.sonar.sound_speed_mps);
  EXPECT_EQ(s.sonar.absorption_db_per_m, d.sonar.absorption_db_per_m);
  EXPECT_EQ(s.sonar.gain_db, d.sonar.gain_db);
  EXPECT_EQ(s.sonar.tvg_db_per_decade, d.sonar.tvg_db_per_decade);
  EXPECT_EQ(s.sonar.noise_level_db, d.sonar.noise_level_db);
  EXPECT_EQ(s.sonar.display_min_db, d.sonar.display_min_db);
  EXPECT_EQ(s.sonar.display_max_db, d.sonar.display_max_db);
  EXPECT_EQ(s.sonar.speckle, d.sonar.speckle);
  EXPECT_EQ(s.sonar.multipath_bounces, d.sonar.multipath_bounces);
  EXPECT_EQ(s.sonar.min_range_m, d.sonar.min_range_m);
  EXPECT_EQ(s.sonar.mount.x_m, d.sonar.mount.x_m);
  EXPECT_EQ(s.sonar.mount.y_m, d.sonar.mount.y_m);
  EXPECT_EQ(s.sonar.mount.z_m, d.sonar.mount.z_m);
  EXPECT_EQ(s.sonar.mount.bearing_offset_rad, d.sonar.mount.bearing_offset_rad);
  EXPECT_EQ(s.sonar.mount.bearing_sign, d.sonar.mount.bearing_sign);

  EXPECT_EQ(s.dvl.rate_hz, d.dvl.rate_hz);
  EXPECT_EQ(s.dvl.noise_sigma_mps, d.dvl.noise_sigma_mps);
  EXPECT_EQ(s.dvl.outlier_probability, d.dvl.outlier_probability);
  EXPECT_EQ(s.dvl.outlier_sigma_mps, d.dvl.outlier_sigma_mps);
  EXPECT_EQ(s.dvl.bias_mps, d.dvl.bias_mps);
  EXPECT_EQ(s.dvl.dropout_probability, d.dvl.dropout_probability);
  EXPECT_EQ(s.dvl.degraded_dropout_probability, d.dvl.degraded_dropout_probability);
  EXPECT_EQ(s.dvl.degraded_fraction, d.dvl.degraded_fraction);
  EXPECT_EQ(s.dvl.degraded_duration_s, d.dvl.degraded_duration_s);
  EXPECT_EQ(s.dvl.max_altitude_m, d.dvl.max_altitude_m);
  EXPECT_EQ(s.dvl.mount.yaw_deg, d.dvl.mount.yaw_deg);
  EXPECT_EQ(s.dvl.mount.x_m, d.dvl.mount.x_m);
  EXPECT_EQ(s.dvl.mount.y_m, d.dvl.mount.y_m);

  EXPECT_EQ(s.mru.rate_hz, d.mru.rate_hz);
  EXPECT_EQ(s.mru.heading_noise_deg, d.mru.heading_noise_deg);
  EXPECT_EQ(s.mru.bias_initial_deg, d.mru.bias_initial_deg);
  EXPECT_EQ(s.mru.bias_random_walk_deg_per_sqrt_s, d.mru.bias_random_walk_deg_per_sqrt_s);
  EXPECT_EQ(s.mru.mount.yaw_offset_deg, d.mru.mount.yaw_offset_deg);

  EXPECT_EQ(s.gps.enabled, d.gps.enabled);
  EXPECT_EQ(s.gps.rate_hz, d.gps.rate_hz);
  EXPECT_EQ(s.gps.noise_sigma_m, d.gps.noise_sigma_m);
  EXPECT_EQ(s.gps.correlated_sigma_m, d.gps.correlated_sigma_m);
  EXPECT_EQ(s.gps.correlation_time_s, d.gps.correlation_time_s);
  EXPECT_EQ(s.gps.tether_length_m, d.gps.tether_length_m);
  EXPECT_EQ(s.gps.frame.origin_latitude_deg, d.gps.frame.origin_latitude_deg);
  EXPECT_EQ(s.gps.frame.origin_longitude_deg, d.gps.frame.origin_longitude_deg);
  EXPECT_TRUE(s.segments.empty());
}

// The St. Pere setup of docs/interfaces.md, written out independently of sim/scenario.hpp.
TEST(ScenarioYaml, DefaultsAreTheStPereSetup) {
  const TempDir dir;
  const sim::Scenario s = read_scenario(write_text(dir.file("s.yaml"), kMinimal));
  EXPECT_EQ(s.sonar.steps_per_revolution, 200);
  EXPECT_EQ(s.sonar.revolution_s, 13.8);
  EXPECT_EQ(s.sonar.bins, 500);
  EXPECT_EQ(s.sonar.bin_m, 0.1);
  EXPECT_EQ(s.dvl.rate_hz, 1.5);
  EXPECT_EQ(s.mru.rate_hz, 10.0);
  EXPECT_EQ(s.mru.mount.yaw_offset_deg, 86.0);
  EXPECT_EQ(s.dvl.mount.yaw_deg, 293.5);
  EXPECT_EQ(s.sonar.mount.x_m, 0.33);
  EXPECT_NEAR(s.sonar.mount.bearing_offset_rad, kPi, kScenarioAngleTolerance_rad);
  EXPECT_EQ(s.sonar.mount.bearing_sign, -1.0);
  EXPECT_TRUE(s.gps.enabled);
}

TEST(ScenarioYaml, EverySectionOverrides) {
  const TempDir dir;
  const std::string text = std::string(kMinimal) +
                           "name: basin test\n"
                           "segments: {first: [0, 30], second: [30, 75.5]}\n"
                           "sonar:\n"
                           "  steps_per_revolution: 100\n"
                           "  revolution_s: 6.9\n"
                           "  bins: 250\n"
                           "  bin_m: 0.2\n"
                           "  horizontal_beamwidth_deg: 2.5\n"
                           "  vertical_beamwidth_deg: 30\n"
                           "  tilt_deg: 5\n"
                           "  rays_horizontal: 2\n"
                           "  rays_vertical: 12\n"
                           "  sound_speed_mps: 1480\n"
                           "  absorption_db_per_m: 0.02\n"
                           "  gain_db: 40\n"
                           "  tvg_db_per_decade: 20\n"
                           "  noise_level_db: -50\n"
                           "  display_min_db: -5\n"
                           "  display_max_db: 40\n"
                           "  speckle: false\n"
                           "  multipath_bounces: 2\n"
                           "  min_range_m: 0.5\n"
                           "  mount: {x_m: 0.4, y_m: -0.1, z_m: 0.2, bearing_offset_deg: 90,"
                           " bearing_sign: 1}\n"
                           "dvl:\n"
                           "  rate_hz: 3\n"
                           "  noise_sigma_mps: 0.05\n"
                           "  outlier_probability: 0.1\n"
                           "  outlier_sigma_mps: 0.5\n"
                           "  bias_mps: [0.01, -0.02]\n"
                           "  dropout_probability: 0.1\n"
                           "  degraded_dropout_probability: 0.6\n"
                           "  degraded_fraction: 0.05\n"
                           "  degraded_duration_s: 12\n"
                           "  max_altitude_m: 20\n"
                           "  mount: {yaw_deg: 45, x_m: 0.2, y_m: 0.1}\n"
                           "mru:\n"
                           "  rate_hz: 20\n"
                           "  heading_noise_deg: 0.5\n"
                           "  bias_initial_deg: 1.5\n"
                           "  bias_random_walk_deg_per_sqrt_s: 0.02\n"
                           "  mount: {yaw_offset_deg: 10}\n"
                           "gps:\n"
                           "  enabled: false\n"
                           "  rate_hz: 2\n"
                           "  noise_sigma_m: 3\n"
                           "  correlated_sigma_m: 2\n"
                           "  correlation_time_s: 300\n"
                           "  tether_length_m: 4.5\n"
                           "  origin_latitude_deg: 41.5\n"
                           "  origin_longitude_deg: 2.25\n";
  const sim::Scenario s = read_scenario(write_text(dir.file("s.yaml"), text));
  EXPECT_EQ(s.name, "basin test");
  ASSERT_EQ(s.segments.size(), 2u);
  EXPECT_EQ(s.segments[0].name, "first");
  EXPECT_EQ(s.segments[0].begin_s, 0.0);
  EXPECT_EQ(s.segments[0].end_s, 30.0);
  EXPECT_EQ(s.segments[1].name, "second");
  EXPECT_EQ(s.segments[1].begin_s, 30.0);
  EXPECT_EQ(s.segments[1].end_s, 75.5);

  EXPECT_EQ(s.sonar.steps_per_revolution, 100);
  EXPECT_EQ(s.sonar.revolution_s, 6.9);
  EXPECT_EQ(s.sonar.bins, 250);
  EXPECT_EQ(s.sonar.bin_m, 0.2);
  EXPECT_EQ(s.sonar.horizontal_beamwidth_deg, 2.5);
  EXPECT_EQ(s.sonar.vertical_beamwidth_deg, 30.0);
  EXPECT_EQ(s.sonar.tilt_deg, 5.0);
  EXPECT_EQ(s.sonar.rays_horizontal, 2);
  EXPECT_EQ(s.sonar.rays_vertical, 12);
  EXPECT_EQ(s.sonar.sound_speed_mps, 1480.0);
  EXPECT_EQ(s.sonar.absorption_db_per_m, 0.02);
  EXPECT_EQ(s.sonar.gain_db, 40.0);
  EXPECT_EQ(s.sonar.tvg_db_per_decade, 20.0);
  EXPECT_EQ(s.sonar.noise_level_db, -50.0);
  EXPECT_EQ(s.sonar.display_min_db, -5.0);
  EXPECT_EQ(s.sonar.display_max_db, 40.0);
  EXPECT_FALSE(s.sonar.speckle);
  EXPECT_EQ(s.sonar.multipath_bounces, 2);
  EXPECT_EQ(s.sonar.min_range_m, 0.5);
  EXPECT_EQ(s.sonar.mount.x_m, 0.4);
  EXPECT_EQ(s.sonar.mount.y_m, -0.1);
  EXPECT_EQ(s.sonar.mount.z_m, 0.2);
  EXPECT_NEAR(s.sonar.mount.bearing_offset_rad, kPi / 2.0, kScenarioAngleTolerance_rad);
  EXPECT_EQ(s.sonar.mount.bearing_sign, 1.0);

  EXPECT_EQ(s.dvl.rate_hz, 3.0);
  EXPECT_EQ(s.dvl.noise_sigma_mps, 0.05);
  EXPECT_EQ(s.dvl.outlier_probability, 0.1);
  EXPECT_EQ(s.dvl.outlier_sigma_mps, 0.5);
  EXPECT_EQ(s.dvl.bias_mps, Eigen::Vector2d(0.01, -0.02));
  EXPECT_EQ(s.dvl.dropout_probability, 0.1);
  EXPECT_EQ(s.dvl.degraded_dropout_probability, 0.6);
  EXPECT_EQ(s.dvl.degraded_fraction, 0.05);
  EXPECT_EQ(s.dvl.degraded_duration_s, 12.0);
  EXPECT_EQ(s.dvl.max_altitude_m, 20.0);
  EXPECT_EQ(s.dvl.mount.yaw_deg, 45.0);
  EXPECT_EQ(s.dvl.mount.x_m, 0.2);
  EXPECT_EQ(s.dvl.mount.y_m, 0.1);

  EXPECT_EQ(s.mru.rate_hz, 20.0);
  EXPECT_EQ(s.mru.heading_noise_deg, 0.5);
  EXPECT_EQ(s.mru.bias_initial_deg, 1.5);
  EXPECT_EQ(s.mru.bias_random_walk_deg_per_sqrt_s, 0.02);
  EXPECT_EQ(s.mru.mount.yaw_offset_deg, 10.0);

  EXPECT_FALSE(s.gps.enabled);
  EXPECT_EQ(s.gps.rate_hz, 2.0);
  EXPECT_EQ(s.gps.noise_sigma_m, 3.0);
  EXPECT_EQ(s.gps.correlated_sigma_m, 2.0);
  EXPECT_EQ(s.gps.correlation_time_s, 300.0);
  EXPECT_EQ(s.gps.tether_length_m, 4.5);
  EXPECT_EQ(s.gps.frame.origin_latitude_deg, 41.5);
  EXPECT_EQ(s.gps.frame.origin_longitude_deg, 2.25);
}

TEST(ScenarioYaml, VehicleOverrides) {
  const TempDir dir;
  const std::string text = std::string(kMinimal) +
                           "  max_turn_rate_deg_s: 12\n"
                           "  lookahead_m: 2\n"
                           "  start_time_s: 1000\n"
                           "  step_s: 0.05\n";
  const sim::Scenario s = read_scenario(write_text(dir.file("s.yaml"), text));
  EXPECT_NEAR(s.vehicle.max_turn_rate_radps, 12.0 * kPi / 180.0, 1e-15);
  EXPECT_EQ(s.vehicle.lookahead_m, 2.0);
  EXPECT_EQ(s.vehicle.start_time_s, 1000.0);
  EXPECT_EQ(s.vehicle.step_s, 0.05);
}

TEST(ScenarioYaml, SceneMaterialsAndGroups) {
  const TempDir dir;
  const std::string text = minimal_with(3,
                                        "  mesh: basin.obj\n"
                                        "  backscatter: 0.6\n"
                                        "  specular: 0.2\n"
                                        "  incidence_exponent: 1.5\n"
                                        "  groups:\n"
                                        "    walls: {backscatter: 0.9, specular: 0.1, "
                                        "incidence_exponent: 0.5}\n"
                                        "    bottom: {backscatter: 0.4}\n"
                                        "  surface: {backscatter: 0.01, specular: 0.95}\n");
  const sim::Scenario s = read_scenario(write_text(dir.file("s.yaml"), text));
  EXPECT_EQ(s.scene.default_material.backscatter, 0.6f);
  EXPECT_EQ(s.scene.default_material.specular, 0.2f);
  ASSERT_EQ(s.scene.group_materials.size(), 2u);
  const sim::Material& walls = s.scene.group_materials.at("walls");
  EXPECT_EQ(walls.name, "walls");
  EXPECT_EQ(walls.backscatter, 0.9f);
  EXPECT_EQ(walls.specular, 0.1f);
  EXPECT_EQ(walls.incidence_exponent, 0.5f);
  EXPECT_EQ(s.scene.default_material.incidence_exponent, 1.5f);
  // A group that sets one value keeps the scene's default for the other.
  const sim::Material& bottom = s.scene.group_materials.at("bottom");
  EXPECT_EQ(bottom.name, "bottom");
  EXPECT_EQ(bottom.backscatter, 0.4f);
  EXPECT_EQ(bottom.specular, 0.2f);
  EXPECT_EQ(bottom.incidence_exponent, 1.5f);
  EXPECT_EQ(s.scene.surface.incidence_exponent, 2.0f);  // Lambert unless set
  EXPECT_EQ(s.scene.surface.name, "water_surface");
  EXPECT_EQ(s.scene.surface.backscatter, 0.01f);
  EXPECT_EQ(s.scene.surface.specular, 0.95f);
}

// The defaults a first scene lives with (docs/scenes.md): concrete walls, a mud floor 22 dB darker.
TEST(ScenarioYaml, DefaultMaterialsAreAHarbours) {
  const sim::SceneConfig d;
  EXPECT_EQ(d.default_material.backscatter, 0.5f);
  EXPECT_EQ(d.default_material.specular, 0.05f);
  EXPECT_EQ(d.bottom_material.backscatter, 0.003f);
  EXPECT_EQ(d.bottom_material.specular, 0.3f);
  EXPECT_LT(10.0 * std::log10(d.bottom_material.backscatter / d.default_material.backscatter),
            -20.0);
}

TEST(ScenarioYaml, SceneBottomSetsTheDefaultFloorMaterial) {
  const TempDir dir;
  const sim::Scenario s = read_scenario(write_text(
      dir.file("s.yaml"),
      minimal_with(3,
                   "  mesh: basin.obj\n  bottom: {backscatter: 0.01, incidence_exponent: 1}\n")));
  EXPECT_EQ(s.scene.bottom_material.backscatter, 0.01f);
  EXPECT_EQ(s.scene.bottom_material.specular, 0.3f);
  EXPECT_EQ(s.scene.bottom_material.incidence_exponent, 1.0f);
  EXPECT_EQ(s.scene.default_material.backscatter, 0.5f);
  expect_bad(minimal_with(3, "  mesh: basin.obj\n  bottom: {backscatter: 2}\n"), 4,
             "scene.bottom.backscatter", "[0, 1]");
  expect_bad(minimal_with(3, "  mesh: basin.obj\n  bottom: {specullar: 0.1}\n"), 4,
             "scene.bottom.specullar", "did you mean 'specular'?");
}

TEST(ScenarioYaml, MeshPathIsRelativeToTheScenarioFolder) {
  const TempDir dir;
  fs::create_directories(dir.path() / "scenarios");
  const std::string path =
      write_text(dir.file("scenarios/s.yaml"), minimal_with(3, "  mesh: ../scenes/basin.obj\n"));
  EXPECT_EQ(read_scenario(path).scene.mesh_path, (dir.path() / "scenes" / "basin.obj").string());

  const std::string absolute = (dir.path() / "elsewhere" / "m.ply").string();
  write_text(path, minimal_with(3, "  mesh: " + absolute + "\n"));
  EXPECT_EQ(read_scenario(path).scene.mesh_path, absolute);
}

TEST(ScenarioYaml, UnknownKeys) {
  expect_bad(std::string(kMinimal) + "sonnar: {}\n", 8, "sonnar");
  expect_bad(std::string(kMinimal) + "sonar:\n  bins: 100\n  bems: 3\n", 10, "sonar.bems");
  expect_bad(minimal_with(3, "  mesh: a.obj\n  meshes: b.obj\n"), 4, "scene.meshes");
  expect_bad(std::string(kMinimal) + "  speed: 1\n", 8, "vehicle.speed");
  expect_bad(std::string(kMinimal) + "dvl: {mount: {yaw: 3}}\n", 8, "dvl.mount.yaw");
  expect_bad(std::string(kMinimal) + "gps: {enable: false}\n", 8, "gps.enable");
  expect_bad(minimal_with(3, "  mesh: a.obj\n  groups: {walls: {backscater: 0.5}}\n"), 4,
             "scene.groups.walls.backscater");
}

TEST(ScenarioYaml, MissingRequiredKeys) {
  expect_bad(minimal_with(1, ""), 0, "seed", "required");
  expect_bad(
      "seed: 7\n"
      "vehicle: {depth_m: 1.5, speed_mps: 0.5, path: [[0, 0], [10, 0]]}\n",
      0, "scene", "required");
  expect_bad(minimal_with(3, "  backscatter: 0.5\n"), 0, "scene.mesh", "required");
  expect_bad(minimal_with(3, "  groups: {}\n"), 0, "scene.mesh", "required");
  expect_bad(
      "seed: 7\n"
      "scene: {mesh: basin.obj}\n",
      0, "vehicle", "required");
  expect_bad(minimal_with(5, ""), 0, "vehicle.depth_m", "required");
  expect_bad(minimal_with(6, ""), 0, "vehicle.speed_mps", "required");
}

// A misspelt key, required or optional, is named at its own line with the known key nearest to it;
// before, a misspelt required key was reported as the required key missing.
TEST(ScenarioYaml, MisspeltKeysAreNamedWithTheClosestKnownKey) {
  expect_bad(minimal_with(6, "  sped_mps: 0.5\n"), 6, "vehicle.sped_mps",
             "unknown key (did you mean 'speed_mps'?)");
  expect_bad(minimal_with(5, "  depht_m: 1.5\n"), 5, "vehicle.depht_m", "did you mean 'depth_m'?");
  expect_bad(minimal_with(7, "  pth: [[0, 0], [10, 0]]\n"), 7, "vehicle.pth",
             "did you mean 'path'?");
  expect_bad(minimal_with(3, "  mseh: basin.obj\n"), 3, "scene.mseh", "did you mean 'mesh'?");
  expect_bad(minimal_with(1, "sed: 7\n"), 1, "sed", "did you mean 'seed'?");
  expect_bad(minimal_with(4, "vehicel:\n"), 4, "vehicel", "did you mean 'vehicle'?");
  expect_bad(minimal_with(2, "scen:\n"), 2, "scen", "did you mean 'scene'?");
  // Optional keys, as before, but with the nearest one rather than the whole list.
  expect_bad(std::string(kMinimal) + "sonar: {bims: 100}\n", 8, "sonar.bims",
             "did you mean 'bins'?");
  expect_bad(std::string(kMinimal) + "sonnar: {}\n", 8, "sonnar", "did you mean 'sonar'?");
  // Nothing near: the known keys are listed.
  expect_bad(std::string(kMinimal) + "sonar: {xyzzy: 1}\n", 8, "sonar.xyzzy", "known here: ");
  // A required key far from every key present is still missing, at its mapping's line.
  expect_bad(minimal_with(6, "  knots: 1\n"), 4, "vehicle.speed_mps", "is required");
}

TEST(YamlFields, ClosestKeyCountsOneEditPerTypo) {
  const std::vector<std::string> known = {"speed_mps", "depth_m", "path", "seed", "scene"};
  EXPECT_EQ(io::closest_key("sped_mps", known), "speed_mps");    // a deletion
  EXPECT_EQ(io::closest_key("speeed_mps", known), "speed_mps");  // an insertion
  EXPECT_EQ(io::closest_key("depht_m", known), "depth_m");       // a swap of neighbours
  EXPECT_EQ(io::closest_key("seen", known), "seed");             // a substitution
  EXPECT_EQ(io::closest_key("speed_mps", known), "");            // itself is not a typo
  EXPECT_EQ(io::closest_key("pathway", known), "");              // 3 edits from a 4-letter key
  EXPECT_EQ(io::closest_key("depth", known), "depth_m");         // 2 edits from a 7-letter key
  EXPECT_EQ(io::closest_key("spd", known), "");
}

// A section written with no value (`scene:`) is an empty mapping: its missing keys are reported
// at the section's own line, not at the line after it (or past the end of the file).
TEST(ScenarioYaml, EmptySectionReportsItsKeyLine) {
  expect_bad(minimal_with(3, ""), 2, "scene.mesh", "required");
  expect_bad("seed: 7\nscene: {mesh: basin.obj}\nvehicle:\n", 3, "vehicle.depth_m", "required");
}

// Separate from the above so that its failure names the one key whose message is wrong.
TEST(ScenarioYaml, MissingPathIsCalledRequired) {
  expect_bad(minimal_with(7, ""), 0, "vehicle.path", "is required");
}

TEST(ScenarioYaml, WrongTypesAndNonFiniteNumbers) {
  expect_bad(minimal_with(6, "  speed_mps: fast\n"), 6, "vehicle.speed_mps");
  expect_bad(minimal_with(6, "  speed_mps: .nan\n"), 6, "vehicle.speed_mps");
  expect_bad(minimal_with(5, "  depth_m: .inf\n"), 5, "vehicle.depth_m");
  expect_bad(minimal_with(1, "seed: seven\n"), 1, "seed");
  expect_bad(minimal_with(1, "seed: 4.5\n"), 1, "seed");
  expect_bad(minimal_with(1, "seed: 99999999999999999999999\n"), 1, "seed");
  expect_bad(minimal_with(1, "seed:\n"), 1, "seed");
  expect_bad(minimal_with(3, "  mesh: [a.obj]\n"), 3, "scene.mesh");
  expect_bad(minimal_with(7, "  path: 3\n"), 7, "vehicle.path");
  expect_bad(std::string(kMinimal) + "sonar: {bins: many}\n", 8, "sonar.bins");
  expect_bad(std::string(kMinimal) + "sonar:\n  speckle: maybe\n", 9, "sonar.speckle");
  expect_bad(std::string(kMinimal) + "gps: {enabled: yes}\n", 8, "gps.enabled");
  expect_bad(std::string(kMinimal) + "dvl: {bias_mps: 0.1}\n", 8, "dvl.bias_mps");
  expect_bad(std::string(kMinimal) + "sonar: 3\n", 8, "sonar");
}

// The sonar model's terms and the detector: read when given, checked when wrong.
TEST(ScenarioYaml, SonarPhysicsAndDetectorKeys) {
  const TempDir dir;
  const std::string path = write_text(
      dir.file("s.yaml"),
      std::string(kMinimal) +
          "sonar: {beam_pattern: sinc, horizontal_span_beamwidths: 3, footprint: false,\n"
          "        pulse_length_us: 100, receiver_time_constant_us: 0, roughness_db: 4,\n"
          "        roughness_length_m: 2.5, speckle_looks: 3}\n"
          "detections: {smoothing_bins: 3, ramp_max: 20, threshold: 50, min_range_m: 1.5}\n");
  const sim::Scenario s = read_scenario(path);
  EXPECT_EQ(s.sonar.beam_pattern, sim::BeamPattern::kSinc);
  EXPECT_EQ(s.sonar.horizontal_span_beamwidths, 3.0);
  EXPECT_FALSE(s.sonar.footprint);
  EXPECT_EQ(s.sonar.pulse_length_us, 100.0);
  EXPECT_EQ(s.sonar.receiver_time_constant_us, 0.0);
  EXPECT_EQ(s.sonar.roughness_db, 4.0);
  EXPECT_EQ(s.sonar.roughness_length_m, 2.5);
  EXPECT_EQ(s.sonar.speckle_looks, 3);
  EXPECT_EQ(s.detections.smoothing_bins, 3);
  EXPECT_EQ(s.detections.ramp_max, 20.0);
  EXPECT_EQ(s.detections.threshold, 50.0);
  EXPECT_EQ(s.detections.min_range_m, 1.5);
  expect_bad(std::string(kMinimal) + "sonar: {beam_pattern: cone}\n", 8, "sonar.beam_pattern");
  expect_bad(std::string(kMinimal) + "sonar:\n  pulse_length_us: -1\n", 9, "sonar.pulse_length_us");
  expect_bad(std::string(kMinimal) + "sonar:\n  roughness_length_m: 0\n", 9,
             "sonar.roughness_length_m");
  expect_bad(std::string(kMinimal) + "sonar:\n  speckle_looks: 0\n", 9, "sonar.speckle_looks");
  // stop_s: the sonar logs until then (s from the start); absent, for the whole run.
  EXPECT_FALSE(s.sonar.stop_s);
  EXPECT_EQ(read_scenario(write_text(dir.file("stop.yaml"),
                                     std::string(kMinimal) + "sonar: {stop_s: 3020.5}\n"))
                .sonar.stop_s,
            3020.5);
  expect_bad(std::string(kMinimal) + "sonar:\n  stop_s: 0\n", 9, "sonar.stop_s");
  // vehicle.heading_csv: a heading history beside the scenario (io/heading_csv).
  EXPECT_TRUE(s.vehicle.heading_deg.empty());
  write_text(dir.file("heading.csv"), "t_s,yaw_deg\n0,10\n5.5,-20\n");
  const sim::Scenario crab = read_scenario(
      write_text(dir.file("crab.yaml"), std::string(kMinimal) + "  heading_csv: heading.csv\n"));
  ASSERT_EQ(crab.vehicle.heading_deg.size(), 2u);
  EXPECT_EQ(crab.vehicle.heading_deg[1], Eigen::Vector2d(5.5, -20.0));
  expect_bad(std::string(kMinimal) + "  heading_csv: none.csv\n", 8, "vehicle.heading_csv");
  write_text(dir.file("heading.csv"), "t_s,yaw_deg\n0,10\n0,12\n");
  try {
    read_scenario(dir.file("crab.yaml"));
    ADD_FAILURE() << "time that does not increase was read";
  } catch (const io::InputError& e) {
    EXPECT_NE(std::string(e.what()).find("heading.csv:3: time does not increase"),
              std::string::npos)
        << e.what();
  }
  write_text(dir.file("heading.csv"), "t_s,yaw_deg\n0,nan\n1,2\n");
  EXPECT_THROW(read_scenario(dir.file("crab.yaml")), io::InputError);
  write_text(dir.file("heading.csv"), "t_s,yaw_deg\n0,1\n");
  EXPECT_THROW(read_scenario(dir.file("crab.yaml")), io::InputError);
  // MATLAB's window may be even (movmean reaches w/2 back and w/2 - 1 ahead); it is at least 1.
  EXPECT_EQ(read_scenario(write_text(dir.file("even.yaml"),
                                     std::string(kMinimal) + "detections: {smoothing_bins: 4}\n"))
                .detections.smoothing_bins,
            4);
  expect_bad(std::string(kMinimal) + "detections:\n  smoothing_bins: 0\n", 9,
             "detections.smoothing_bins", "[1, 999]");
  // auto: MATLAB's default window, chosen per revolution (smoothing_bins 0 in the config).
  const sim::Scenario automatic = read_scenario(write_text(
      dir.file("auto.yaml"),
      std::string(kMinimal) + "detections: {smoothing_bins: auto, smoothing_factor: 0.3}\n"));
  EXPECT_EQ(automatic.detections.smoothing_bins, 0);
  EXPECT_EQ(automatic.detections.smoothing_factor, 0.3);
  expect_bad(std::string(kMinimal) + "detections:\n  smoothing_factor: 2\n", 9,
             "detections.smoothing_factor", "[0, 1]");
  expect_bad(std::string(kMinimal) + "detections:\n  treshold: 45\n", 9, "detections.treshold");
}

TEST(ScenarioYaml, BadValues) {
  expect_bad(minimal_with(6, "  speed_mps: 0\n"), 6, "vehicle.speed_mps");
  expect_bad(minimal_with(6, "  speed_mps: -0.5\n"), 6, "vehicle.speed_mps");
  expect_bad(minimal_with(5, "  depth_m: -1\n"), 5, "vehicle.depth_m");
  expect_bad(minimal_with(1, "seed: -1\n"), 1, "seed");
  expect_bad(minimal_with(3, "  mesh: basin.obj\n  groups: {walls: {incidence_exponent: -1}}\n"), 4,
             "scene.groups.walls.incidence_exponent");
  expect_bad(std::string(kMinimal) + "sonar:\n  bins: 0\n", 9, "sonar.bins");
  expect_bad(std::string(kMinimal) + "sonar:\n  display_min_db: 10\n  display_max_db: 10\n", 10,
             "sonar.display_max_db");
  expect_bad(std::string(kMinimal) + "sonar:\n  display_min_db: 50\n", 0, "sonar.display_max_db");
  expect_bad(std::string(kMinimal) + "dvl:\n  dropout_probability: 1.5\n", 9,
             "dvl.dropout_probability");
  expect_bad(std::string(kMinimal) + "dvl:\n  bias_mps: [0.1, 0.2, 0.3]\n", 9, "dvl.bias_mps");
  expect_bad(std::string(kMinimal) + "dvl:\n  outlier_probability: -0.1\n", 9,
             "dvl.outlier_probability");
  expect_bad(std::string(kMinimal) + "dvl:\n  outlier_sigma_mps: -1\n", 9, "dvl.outlier_sigma_mps");
  expect_bad(std::string(kMinimal) + "dvl:\n  degraded_dropout_probability: 2\n", 9,
             "dvl.degraded_dropout_probability");
  expect_bad(std::string(kMinimal) + "dvl:\n  rate_hz: 2\n  degraded_fraction: 1\n", 10,
             "dvl.degraded_fraction");
  expect_bad(std::string(kMinimal) + "dvl:\n  degraded_duration_s: 0\n", 9,
             "dvl.degraded_duration_s");
  expect_bad(std::string(kMinimal) + "gps:\n  correlated_sigma_m: -0.5\n", 9,
             "gps.correlated_sigma_m");
  expect_bad(std::string(kMinimal) + "gps:\n  correlation_time_s: 0\n", 9,
             "gps.correlation_time_s");
  expect_bad(std::string(kMinimal) + "gps:\n  tether_length_m: -2\n", 9, "gps.tether_length_m");
  expect_bad(minimal_with(3, "  mesh: basin.obj\n  backscatter: 2\n"), 4, "scene.backscatter");
  expect_bad(minimal_with(3, "  mesh: basin.obj\n  groups: {walls: {specular: -0.1}}\n"), 4,
             "scene.groups.walls.specular");
  expect_bad(std::string(kMinimal) + "segments: {loop: [30, 10]}\n", 8, "segments.loop");
  expect_bad(std::string(kMinimal) + "sonar: {mount: {bearing_sign: 0.5}}\n", 8,
             "sonar.mount.bearing_sign");
  expect_bad(std::string(kMinimal) + "sonar:\n  water_sound_speed_mps: 150\n", 9,
             "sonar.water_sound_speed_mps");
  expect_bad(std::string(kMinimal) + "dvl:\n  scale_factor: 0\n", 9, "dvl.scale_factor");
  expect_bad(std::string(kMinimal) + "stated_calibration:\n  sonar: {time_offset_s: 90}\n", 9,
             "stated_calibration.sonar.time_offset_s");
  expect_bad(std::string(kMinimal) + "stated_calibration:\n  dvl: {scale: 1}\n", 9,
             "stated_calibration.dvl.scale");
}

TEST(ScenarioYaml, RotationAndSectorScan) {
  const TempDir dir;
  const sim::Scenario whole = read_scenario(write_text(dir.file("w.yaml"), kMinimal));
  EXPECT_EQ(whole.sonar.rotation, sim::SonarRotation::kDecreasing);
  EXPECT_FALSE(whole.sonar.sector);
  const sim::Scenario sector = read_scenario(write_text(
      dir.file("s.yaml"), std::string(kMinimal) +
                              "sonar:\n  steps_per_revolution: 400\n  rotation: increasing\n"
                              "  sector_deg: [-45, 45.2]\n"));
  EXPECT_EQ(sector.sonar.rotation, sim::SonarRotation::kIncreasing);
  ASSERT_TRUE(sector.sonar.sector);
  EXPECT_EQ(sector.sonar.sector->first_index, 350);  // -45 deg: 315 deg, 350 gradians
  EXPECT_EQ(sector.sonar.sector->last_index, 50);    // 45.2 deg rounds to 45
  expect_bad(std::string(kMinimal) + "sonar:\n  rotation: clockwise\n", 9, "sonar.rotation",
             "must be 'decreasing' or 'increasing'");
  expect_bad(std::string(kMinimal) + "sonar:\n  sector_deg: [10]\n", 9, "sonar.sector_deg");
  expect_bad(std::string(kMinimal) + "sonar:\n  sector_deg: [0, 360]\n", 9, "sonar.sector_deg",
             "the same step");
}

// Errors the estimators are to find: a sound speed the sonar does not know, a DVL scale factor,
// and a calibration.yaml that states other values than the sensors have (every other key of it
// keeps the sensors' own value).
TEST(ScenarioYaml, InjectedCalibrationErrors) {
  const TempDir dir;
  const sim::Scenario plain = read_scenario(write_text(dir.file("p.yaml"), kMinimal));
  EXPECT_FALSE(plain.sonar.water_sound_speed_mps);
  EXPECT_EQ(plain.dvl.scale_factor, 1.0);
  EXPECT_FALSE(plain.stated_calibration);
  const sim::Scenario s = read_scenario(write_text(
      dir.file("s.yaml"), std::string(kMinimal) +
                              "sonar: {water_sound_speed_mps: 1440, mount: {time_offset_s: 0.66}}\n"
                              "dvl: {scale_factor: 1.01}\n"
                              "mru: {deviation_cos_deg: 0.62, deviation_sin_deg: -3.39}\n"
                              "stated_calibration:\n"
                              "  mru: {deviation_cos_deg: 0, deviation_sin_deg: 0}\n"
                              "  sonar: {time_offset_s: 0}\n"));
  EXPECT_EQ(*s.sonar.water_sound_speed_mps, 1440.0);
  EXPECT_EQ(s.dvl.scale_factor, 1.01);
  const Calibration truth = sim::true_calibration(s), stated = sim::calibration_of(s);
  EXPECT_EQ(truth.mru.deviation_cos_deg, 0.62);
  EXPECT_EQ(truth.sonar.time_offset_s, 0.66);
  EXPECT_EQ(stated.mru.deviation_cos_deg, 0.0);
  EXPECT_EQ(stated.mru.deviation_sin_deg, 0.0);
  EXPECT_EQ(stated.sonar.time_offset_s, 0.0);
  EXPECT_EQ(stated.mru.yaw_offset_deg, truth.mru.yaw_offset_deg);
  EXPECT_EQ(stated.dvl.yaw_deg, truth.dvl.yaw_deg);
  EXPECT_EQ(stated.sonar.x_m, truth.sonar.x_m);
  EXPECT_EQ(stated.frame.origin_latitude_deg, truth.frame.origin_latitude_deg);
}

TEST(ScenarioYaml, BadPaths) {
  expect_bad(minimal_with(7, "  path: [[0, 0]]\n"), 7, "vehicle.path");
  expect_bad(minimal_with(7, "  path: []\n"), 7, "vehicle.path");
  expect_bad(minimal_with(7, "  path: [[0, 0], [1, 2, 3]]\n"), 7, "vehicle.path");
  expect_bad(minimal_with(7, "  path: [[0, 0], [1, .nan]]\n"), 7, "vehicle.path");
  expect_bad(minimal_with(7, "  path: [[0, 0], [1, east]]\n"), 7, "vehicle.path");
  expect_bad(minimal_with(7, "  path: [[0, 0], [5, 5], [5, 5], [9, 9]]\n"), 7, "vehicle.path");
  expect_bad(minimal_with(7,
                          "  path:\n"
                          "    - [0, 0]\n"
                          "    - [4, 0]\n"
                          "    - [4, 0, 1]\n"),
             10, "vehicle.path");
}

TEST(ScenarioYaml, LegSpeedsOnePerLeg) {
  const TempDir dir;
  const std::string text = std::string(kMinimal) + "  leg_speeds_mps: [0.2, 0.05]\n";
  const sim::Scenario s = read_scenario(write_text(dir.file("s.yaml"), text));
  EXPECT_EQ(s.vehicle.leg_speeds_mps, (std::vector<double>{0.2, 0.05}));
  EXPECT_TRUE(
      read_scenario(write_text(dir.file("m.yaml"), kMinimal)).vehicle.leg_speeds_mps.empty());
  expect_bad(std::string(kMinimal) + "  leg_speeds_mps: [0.2]\n", 8, "vehicle.leg_speeds_mps",
             "expected 2 speeds (one per leg), got 1");
  expect_bad(std::string(kMinimal) + "  leg_speeds_mps: [0.2, 0.1, 0.3]\n", 8,
             "vehicle.leg_speeds_mps", "got 3");
  expect_bad(std::string(kMinimal) + "  leg_speeds_mps: [0.2, 0]\n", 8, "vehicle.leg_speeds_mps",
             "must be > 0");
  expect_bad(std::string(kMinimal) + "  leg_speeds_mps: [0.2, fast]\n", 8,
             "vehicle.leg_speeds_mps");
  expect_bad(std::string(kMinimal) + "  leg_speed_mps: [0.2, 0.1]\n", 8, "vehicle.leg_speed_mps");
}

TEST(ScenarioYaml, MalformedYamlAndDuplicateKeys) {
  expect_bad(minimal_with(6, "  speed_mps: [0.5\n"), 0, "", "malformed YAML");
  expect_bad(minimal_with(6, "  speed_mps: 0.5\n  speed_mps: 0.7\n"), 7, "vehicle.speed_mps",
             "duplicate key");
  expect_bad(std::string(kMinimal) + "seed: 8\n", 8, "seed");
  expect_bad("- seed: 7\n", 1, "");
}

TEST(ScenarioYaml, MissingFileNamesTheFile) {
  const TempDir dir;
  const std::string path = dir.file("no_such_scenario.yaml");
  try {
    read_scenario(path);
    ADD_FAILURE() << "no InputError";
  } catch (const io::InputError& e) {
    EXPECT_EQ(std::string(e.what()).rfind(path + ": ", 0), 0u) << e.what();
  }
}

}  // namespace
}  // namespace msislab::settings
