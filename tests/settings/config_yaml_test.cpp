// calibration.yaml and the SLAM config: defaults when keys are absent, overrides, the exact write
// -> read round trip, and every class of bad input rejected with "FILE:LINE: key 'a.b': ...".
#include "settings/config_yaml.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <string>

#include "geometry/angles.hpp"
#include "geometry/calibration.hpp"
#include "io/input_error.hpp"
#include "test_support.hpp"

namespace msislab::settings {
namespace {

using testing::TempDir;
using testing::write_text;

constexpr double kAngleTolerance_rad = 1e-12;

// Expects `read(path)` to throw InputError whose message contains the file, ":LINE:" and, when
// given, the quoted dotted key.
template <typename Read>
void expect_input_error(Read read, const std::string& path, int line, const std::string& key) {
  try {
    read(path);
    ADD_FAILURE() << "no InputError for " << path;
  } catch (const io::InputError& e) {
    const std::string message = e.what();
    const std::string where = path + ":" + std::to_string(line) + ":";
    EXPECT_NE(message.find(where), std::string::npos) << message << "\nexpected " << where;
    if (!key.empty()) {
      EXPECT_NE(message.find("key '" + key + "'"), std::string::npos)
          << message << "\nexpected key '" << key << "'";
    }
  }
}

void expect_bad_calibration(const std::string& text, int line, const std::string& key) {
  const TempDir dir;
  const std::string path = write_text(dir.file("calibration.yaml"), text);
  expect_input_error([](const std::string& p) { read_calibration(p); }, path, line, key);
}

void expect_bad_slam_config(const std::string& text, int line, const std::string& key) {
  const TempDir dir;
  const std::string path = write_text(dir.file("slam.yaml"), text);
  expect_input_error([](const std::string& p) { read_slam_config(p); }, path, line, key);
}

// The St. Pere values of geometry/calibration.hpp and the dataset README, written out
// independently.
void expect_stpere_calibration(const Calibration& c) {
  EXPECT_EQ(c.mru.yaw_offset_deg, 86.0);
  EXPECT_EQ(c.dvl.yaw_deg, 293.5);
  EXPECT_EQ(c.dvl.x_m, 0.0);
  EXPECT_EQ(c.dvl.y_m, 0.0);
  EXPECT_EQ(c.sonar.x_m, 0.33);
  EXPECT_EQ(c.sonar.y_m, 0.0);
  EXPECT_NEAR(c.sonar.bearing_offset_rad, kPi, kAngleTolerance_rad);
  EXPECT_EQ(c.sonar.bearing_sign, -1.0);
  EXPECT_EQ(c.sonar.time_offset_s, 0.66);
  EXPECT_EQ(c.frame.origin_latitude_deg, 42.0 + 12.225 / 60.0);
  EXPECT_EQ(c.frame.origin_longitude_deg, 3.0 + 6.2832 / 60.0);
}

TEST(CalibrationYaml, AbsentKeysKeepTheStPereDefaults) {
  const TempDir dir;
  expect_stpere_calibration(Calibration{});
  for (const std::string text : {"", "# only a comment\n", "{}\n", "mru: {}\ndvl:\nsonar: {}\n"}) {
    expect_stpere_calibration(read_calibration(write_text(dir.file("c.yaml"), text)));
  }
}

TEST(CalibrationYaml, PartialOverride) {
  const TempDir dir;
  const Calibration c = read_calibration(write_text(dir.file("c.yaml"),
                                                    "dvl:\n"
                                                    "  yaw_deg: 290.25\n"
                                                    "sonar:\n"
                                                    "  bearing_offset_deg: 90\n"
                                                    "  bearing_sign: 1\n"
                                                    "frame: {origin_latitude_deg: -33.5}\n"));
  EXPECT_EQ(c.dvl.yaw_deg, 290.25);
  EXPECT_NEAR(c.sonar.bearing_offset_rad, kPi / 2.0, kAngleTolerance_rad);
  EXPECT_EQ(c.sonar.bearing_sign, 1.0);
  EXPECT_EQ(c.frame.origin_latitude_deg, -33.5);
  // Everything not named keeps its default.
  const Calibration defaults;
  EXPECT_EQ(c.mru.yaw_offset_deg, defaults.mru.yaw_offset_deg);
  EXPECT_EQ(c.dvl.x_m, defaults.dvl.x_m);
  EXPECT_EQ(c.dvl.y_m, defaults.dvl.y_m);
  EXPECT_EQ(c.sonar.x_m, defaults.sonar.x_m);
  EXPECT_EQ(c.sonar.y_m, defaults.sonar.y_m);
  EXPECT_EQ(c.frame.origin_longitude_deg, defaults.frame.origin_longitude_deg);
}

TEST(CalibrationYaml, WriteReadRoundTrip) {
  const TempDir dir;
  Calibration c;
  c.mru.yaw_offset_deg = -86.123456789012345;
  c.mru.deviation_cos_deg = 0.62;
  c.mru.deviation_sin_deg = -2.3900000000000001;
  c.dvl.yaw_deg = 293.49999999999994;
  c.dvl.x_m = 0.1 + 0.2;
  c.dvl.y_m = -1e-17;
  c.sonar.x_m = 0.33333333333333331;
  c.sonar.y_m = -0.05;
  c.sonar.bearing_offset_rad = 2.9876543210987654;
  c.sonar.bearing_sign = 1.0;
  c.sonar.time_offset_s = -0.12345678901234567;
  c.sonar.range_scale = 1500.0 / 1440.0;
  c.dvl.scale_factor = 1.01;
  c.dvl.y_to_starboard = true;
  c.frame.origin_latitude_deg = -12.345678901234567;
  c.frame.origin_longitude_deg = 179.99999999999997;
  const std::string path = dir.file("calibration.yaml");
  write_calibration(path, c);
  const Calibration back = read_calibration(path);
  EXPECT_EQ(back.mru.yaw_offset_deg, c.mru.yaw_offset_deg);
  EXPECT_EQ(back.mru.deviation_cos_deg, c.mru.deviation_cos_deg);
  EXPECT_EQ(back.mru.deviation_sin_deg, c.mru.deviation_sin_deg);
  EXPECT_EQ(back.dvl.yaw_deg, c.dvl.yaw_deg);
  EXPECT_EQ(back.dvl.x_m, c.dvl.x_m);
  EXPECT_EQ(back.dvl.y_m, c.dvl.y_m);
  EXPECT_EQ(back.sonar.x_m, c.sonar.x_m);
  EXPECT_EQ(back.sonar.y_m, c.sonar.y_m);
  // Written in degrees, read back in radians: one conversion each way.
  EXPECT_NEAR(back.sonar.bearing_offset_rad, c.sonar.bearing_offset_rad, kAngleTolerance_rad);
  EXPECT_EQ(back.sonar.bearing_sign, c.sonar.bearing_sign);
  EXPECT_EQ(back.sonar.time_offset_s, c.sonar.time_offset_s);
  EXPECT_EQ(back.sonar.range_scale, c.sonar.range_scale);
  EXPECT_EQ(back.dvl.scale_factor, c.dvl.scale_factor);
  EXPECT_TRUE(back.dvl.y_to_starboard);
  EXPECT_EQ(back.frame.origin_latitude_deg, c.frame.origin_latitude_deg);
  EXPECT_EQ(back.frame.origin_longitude_deg, c.frame.origin_longitude_deg);
  // What a dataset held in memory carries is what the file gives back, to the bit.
  const Calibration stored = calibration_as_stored(c);
  EXPECT_EQ(stored.sonar.bearing_offset_rad, back.sonar.bearing_offset_rad);
  EXPECT_EQ(stored.mru.yaw_offset_deg, back.mru.yaw_offset_deg);
  EXPECT_EQ(stored.frame.origin_longitude_deg, back.frame.origin_longitude_deg);
  // Atomic write: no temporary left beside the file.
  int files = 0;
  for ([[maybe_unused]] const auto& entry : std::filesystem::directory_iterator(dir.path())) {
    ++files;
  }
  EXPECT_EQ(files, 1);
}

TEST(CalibrationYaml, UnknownTopLevelKey) {
  expect_bad_calibration("mru:\n  yaw_offset_deg: 86\nsonr:\n  x_m: 1\n", 3, "sonr");
}

TEST(CalibrationYaml, UnknownNestedKeyTypo) {
  expect_bad_calibration("dvl:\n  yaw_dg: 290\n", 2, "dvl.yaw_dg");
  expect_bad_calibration("mru: {yaw_offset_deg: 86}\n\nframe:\n  origin_lat_deg: 1\n", 4,
                         "frame.origin_lat_deg");
}

TEST(CalibrationYaml, NotANumber) {
  expect_bad_calibration("dvl:\n  x_m: abc\n", 2, "dvl.x_m");
  expect_bad_calibration("dvl:\n  x_m: 1.5m\n", 2, "dvl.x_m");
  expect_bad_calibration("dvl:\n  x_m: [1, 2]\n", 2, "dvl.x_m");
  expect_bad_calibration("mru:\n  yaw_offset_deg: {a: 1}\n", 2, "mru.yaw_offset_deg");
}

TEST(CalibrationYaml, NonFiniteNumbers) {
  expect_bad_calibration("sonar:\n  x_m: .nan\n", 2, "sonar.x_m");
  expect_bad_calibration("sonar:\n  x_m: 0\n  y_m: .inf\n", 3, "sonar.y_m");
  expect_bad_calibration("sonar:\n  bearing_offset_deg: -.inf\n", 2, "sonar.bearing_offset_deg");
  expect_bad_calibration("dvl:\n  yaw_deg: 1e400\n", 2, "dvl.yaw_deg");
}

TEST(CalibrationYaml, BadValues) {
  expect_bad_calibration("sonar:\n  bearing_sign: 2\n", 2, "sonar.bearing_sign");
  expect_bad_calibration("sonar:\n  bearing_sign: 0\n", 2, "sonar.bearing_sign");
  expect_bad_calibration("sonar:\n  time_offset_s: 61\n", 2, "sonar.time_offset_s");
  expect_bad_calibration("mru:\n  deviation_cos_deg: 40\n  deviation_sin_deg: 30\n", 2,
                         "mru.deviation_cos_deg");
  expect_bad_calibration("mru:\n  deviation_sin_deg: .nan\n", 2, "mru.deviation_sin_deg");
  expect_bad_calibration("frame:\n  origin_latitude_deg: 95\n", 2, "frame.origin_latitude_deg");
  expect_bad_calibration("frame:\n  origin_latitude_deg: -84.5\n", 2, "frame.origin_latitude_deg");
  expect_bad_calibration("frame:\n  origin_longitude_deg: 181\n", 2, "frame.origin_longitude_deg");
  expect_bad_calibration("dvl:\n  scale_factor: 0\n", 2, "dvl.scale_factor");
  expect_bad_calibration("dvl:\n  scale_factor: .nan\n", 2, "dvl.scale_factor");
  expect_bad_calibration("sonar:\n  range_scale: 2.5\n", 2, "sonar.range_scale");
  expect_bad_calibration("dvl:\n  y_axis: down\n", 2, "dvl.y_axis");
}

TEST(CalibrationYaml, ADvlWithYToStarboardIsMirroredThenRotated) {
  // Unwritten when to port (the default), so the files of earlier datasets read the same.
  const TempDir dir;
  Calibration c;
  write_calibration(dir.file("port.yaml"), c);
  EXPECT_EQ(testing::read_text(dir.file("port.yaml")).find("y_axis"), std::string::npos);
  c.dvl.yaw_deg = 90.0;
  c.dvl.y_to_starboard = true;
  // DVL x forward of the vehicle's +y, DVL y to starboard of it: the vehicle's +x.
  const Eigen::Vector2d forward = R_vehicle_dvl(c.dvl) * Eigen::Vector2d(1.0, 0.0);
  const Eigen::Vector2d starboard = R_vehicle_dvl(c.dvl) * Eigen::Vector2d(0.0, 1.0);
  EXPECT_NEAR((forward - Eigen::Vector2d(0.0, 1.0)).norm(), 0.0, 1e-15);
  EXPECT_NEAR((starboard - Eigen::Vector2d(1.0, 0.0)).norm(), 0.0, 1e-15);
}

TEST(CalibrationYaml, MalformedSyntaxNamesFileAndLine) {
  expect_bad_calibration("dvl:\n  yaw_deg: 290\n x_m: 1\n", 3, "");
  expect_bad_calibration("dvl:\n  yaw_deg: 290\n\tx_m: 1\n", 3, "");
  expect_bad_calibration("mru: {}\ndvl:\n  yaw_deg: [1, 2]]\n", 3, "");
  expect_bad_calibration("mru:\n  yaw_offset_deg: 86\n  - 2\n", 3, "");
}

// BUG (io/yaml_fields.cpp, YamlMap::finish and YamlMap::number): a repeated key is accepted and
// the first occurrence silently wins, so a second value, or a whole repeated section with a typo
// inside it, is never read nor checked. YAML requires unique keys; these must be InputErrors.
TEST(CalibrationYaml, DuplicateKeysAreRejected) {
  SCOPED_TRACE("BUG: duplicate keys are silently accepted (first occurrence wins)");
  expect_bad_calibration("dvl:\n  yaw_deg: 10\n  yaw_deg: 20\n", 3, "dvl.yaw_deg");
  expect_bad_calibration("dvl: {}\ndvl:\n  yaw_dg: 1\n", 2, "dvl");
}

// BUG (io/yaml_fields.cpp, YamlMap::fail_node): an empty value ("x_m:" with nothing after it) is
// reported at the line of the next token, not at the key's line, and as "a structure".
TEST(CalibrationYaml, EmptyValueIsReportedAtItsKeysLine) {
  SCOPED_TRACE("BUG: an empty value is reported at the next line");
  expect_bad_calibration("dvl:\n  x_m:\n  y_m: 0.5\n", 2, "dvl.x_m");
}

TEST(CalibrationYaml, MissingFile) {
  const TempDir dir;
  const std::string path = dir.file("absent.yaml");
  try {
    read_calibration(path);
    ADD_FAILURE() << "no InputError for a missing file";
  } catch (const io::InputError& e) {
    EXPECT_NE(std::string(e.what()).find(path), std::string::npos) << e.what();
  }
}

TEST(CalibrationYaml, MappingExpectedButListGiven) {
  expect_bad_calibration("mru: {}\ndvl: [1, 2]\n", 2, "dvl");
  expect_bad_calibration("dvl:\n  - yaw_deg: 1\n", 2, "dvl");
  expect_bad_calibration("dvl: 3\n", 1, "dvl");
  // The document itself must be a mapping.
  expect_bad_calibration("- dvl\n- mru\n", 1, "");
}

TEST(SlamConfigYaml, Defaults) {
  const TempDir dir;
  const SlamConfig c = read_slam_config(write_text(dir.file("slam.yaml"), "# defaults\n"));
  const DeadReckoningConfig d;
  EXPECT_EQ(c.dead_reckoning.dvl_sigma_mps, d.dvl_sigma_mps);
  EXPECT_EQ(c.dead_reckoning.heading_sigma_rad, d.heading_sigma_rad);
  EXPECT_EQ(c.dead_reckoning.accel_sigma_mps2, d.accel_sigma_mps2);
  EXPECT_EQ(c.dead_reckoning.yaw_accel_sigma_radps2, d.yaw_accel_sigma_radps2);
  EXPECT_EQ(c.dead_reckoning.initial_velocity_sigma_mps, d.initial_velocity_sigma_mps);
  EXPECT_EQ(c.dead_reckoning.initial_yaw_rate_sigma_radps, d.initial_yaw_rate_sigma_radps);
  EXPECT_EQ(c.dead_reckoning.dvl_gate_chi2, d.dvl_gate_chi2);
  EXPECT_TRUE(c.segments.empty());
}

TEST(SlamConfigYaml, DeadReckoningKeysOverride) {
  const TempDir dir;
  const SlamConfig c = read_slam_config(write_text(dir.file("slam.yaml"),
                                                   "dead_reckoning:\n"
                                                   "  dvl_sigma_mps: 0.05\n"
                                                   "  heading_sigma_deg: 2\n"
                                                   "  accel_sigma_mps2: 0.125\n"
                                                   "  yaw_accel_sigma_radps2: 0.5\n"
                                                   "  initial_velocity_sigma_mps: 1.5\n"
                                                   "  initial_yaw_rate_sigma_radps: 0.25\n"
                                                   "  dvl_gate_chi2: 13.82\n"));
  EXPECT_EQ(c.dead_reckoning.dvl_sigma_mps, 0.05);
  EXPECT_NEAR(c.dead_reckoning.heading_sigma_rad, 2.0 * kPi / 180.0, 1e-15);
  EXPECT_EQ(c.dead_reckoning.accel_sigma_mps2, 0.125);
  EXPECT_EQ(c.dead_reckoning.yaw_accel_sigma_radps2, 0.5);
  EXPECT_EQ(c.dead_reckoning.initial_velocity_sigma_mps, 1.5);
  EXPECT_EQ(c.dead_reckoning.initial_yaw_rate_sigma_radps, 0.25);
  EXPECT_EQ(c.dead_reckoning.dvl_gate_chi2, 13.82);
}

TEST(SlamConfigYaml, JointUpdateKeys) {
  const TempDir dir;
  const SlamConfig defaults = read_slam_config(write_text(dir.file("d.yaml"), "# defaults\n"));
  EXPECT_FALSE(defaults.trajectory_slam.front_end.joint_update);
  EXPECT_TRUE(defaults.trajectory_slam.filter.match_cross_covariance);
  EXPECT_EQ(defaults.trajectory_slam.filter.scan_shared_errors, ScanSharedErrors::kNone);
  const SlamConfig c = read_slam_config(write_text(dir.file("slam.yaml"),
                                                   "trajectory_slam:\n"
                                                   "  joint_update: true\n"
                                                   "  match_cross_covariance: false\n"
                                                   "  scan_shared_errors: motion\n"));
  EXPECT_TRUE(c.trajectory_slam.front_end.joint_update);
  EXPECT_FALSE(c.trajectory_slam.filter.match_cross_covariance);
  EXPECT_EQ(c.trajectory_slam.filter.scan_shared_errors, ScanSharedErrors::kMotion);
  EXPECT_EQ(
      read_slam_config(write_text(dir.file("both.yaml"),
                                  "trajectory_slam:\n  scan_shared_errors: motion_and_points\n"))
          .trajectory_slam.filter.scan_shared_errors,
      ScanSharedErrors::kMotionAndPoints);
  expect_bad_slam_config("trajectory_slam:\n  joint_update: 3\n", 2,
                         "trajectory_slam.joint_update");
  expect_bad_slam_config("trajectory_slam:\n  scan_shared_errors: points\n", 2,
                         "trajectory_slam.scan_shared_errors");
}

TEST(SlamConfigYaml, LinearisationSamplesIsTheStudysKeyNotTheFilters) {
  // trajectory_slam.linearisation_samples switches a study on (SlamConfig::linearisation_samples);
  // the filters' own config does not carry it.
  const TempDir dir;
  const SlamConfig defaults = read_slam_config(write_text(dir.file("d.yaml"), "# defaults\n"));
  EXPECT_EQ(defaults.linearisation_samples, 0);
  const SlamConfig c = read_slam_config(
      write_text(dir.file("slam.yaml"), "trajectory_slam:\n  linearisation_samples: 20\n"));
  EXPECT_EQ(c.linearisation_samples, 20);
  expect_bad_slam_config("trajectory_slam:\n  linearisation_samples: -1\n", 2,
                         "trajectory_slam.linearisation_samples");
}

TEST(SlamConfigYaml, InitialGuessTermKey) {
  const TempDir dir;
  const SlamConfig defaults = read_slam_config(write_text(dir.file("d.yaml"), "# defaults\n"));
  EXPECT_FALSE(defaults.trajectory_slam.front_end.validation.initial_guess_term);
  const SlamConfig c = read_slam_config(write_text(dir.file("slam.yaml"),
                                                   "trajectory_slam:\n"
                                                   "  validation: {initial_guess_term: true}\n"));
  EXPECT_TRUE(c.trajectory_slam.front_end.validation.initial_guess_term);
  expect_bad_slam_config("trajectory_slam:\n  validation: {initial_guess_term: 2}\n", 2,
                         "trajectory_slam.validation.initial_guess_term");
}

TEST(SlamConfigYaml, AmbiguityMinFractionKey) {
  const TempDir dir;
  const SlamConfig defaults = read_slam_config(write_text(dir.file("d.yaml"), "# defaults\n"));
  EXPECT_EQ(defaults.trajectory_slam.front_end.validation.ambiguity_min_fraction, 0.25);
  const SlamConfig c = read_slam_config(write_text(dir.file("slam.yaml"),
                                                   "trajectory_slam:\n"
                                                   "  validation: {ambiguity_min_fraction: 0}\n"));
  EXPECT_EQ(c.trajectory_slam.front_end.validation.ambiguity_min_fraction, 0.0);
  expect_bad_slam_config("trajectory_slam:\n  validation: {ambiguity_min_fraction: 1}\n", 2,
                         "trajectory_slam.validation.ambiguity_min_fraction");
  expect_bad_slam_config("trajectory_slam:\n  validation: {ambiguity_min_fraction: -0.1}\n", 2,
                         "trajectory_slam.validation.ambiguity_min_fraction");
}

TEST(SlamConfigYaml, CalibrationStateKeys) {
  const TempDir dir;
  const SlamConfig defaults = read_slam_config(write_text(dir.file("d.yaml"), "# defaults\n"));
  EXPECT_FALSE(defaults.trajectory_slam.calibration.range_scale);
  EXPECT_EQ(defaults.trajectory_slam.calibration.range_scale_prior, 1.0);
  EXPECT_EQ(defaults.trajectory_slam.calibration.range_scale_sigma, 0.05);
  EXPECT_FALSE(defaults.trajectory_slam.calibration.dvl_scale);
  EXPECT_EQ(defaults.trajectory_slam.calibration.dvl_scale_prior, 1.0);
  EXPECT_EQ(defaults.trajectory_slam.calibration.dvl_scale_sigma, 0.02);
  const SlamConfig c = read_slam_config(
      write_text(dir.file("slam.yaml"),
                 "trajectory_slam:\n"
                 "  calibration: {range_scale: true, range_scale_prior: 0.97,\n"
                 "                range_scale_sigma: 0.02, dvl_scale: true,\n"
                 "                dvl_scale_prior: 1.01, dvl_scale_sigma: 0.005}\n"));
  EXPECT_TRUE(c.trajectory_slam.calibration.range_scale);
  EXPECT_EQ(c.trajectory_slam.calibration.range_scale_prior, 0.97);
  EXPECT_EQ(c.trajectory_slam.calibration.range_scale_sigma, 0.02);
  EXPECT_TRUE(c.trajectory_slam.calibration.dvl_scale);
  EXPECT_EQ(c.trajectory_slam.calibration.dvl_scale_prior, 1.01);
  EXPECT_EQ(c.trajectory_slam.calibration.dvl_scale_sigma, 0.005);
  expect_bad_slam_config("trajectory_slam:\n  calibration: {dvl_scale_sigma: -0.1}\n", 2,
                         "trajectory_slam.calibration.dvl_scale_sigma");
  const SlamConfig more =
      read_slam_config(write_text(dir.file("more.yaml"),
                                  "trajectory_slam:\n"
                                  "  calibration: {clock_offset: true, clock_offset_prior_s: 0.5,\n"
                                  "                clock_offset_sigma_s: 0.2,\n"
                                  "                compass_deviation: true,\n"
                                  "                compass_deviation_cos_prior_deg: 0.6,\n"
                                  "                compass_deviation_sin_prior_deg: -3,\n"
                                  "                compass_deviation_sigma_deg: 1}\n"));
  const CalibrationStatesConfig& m = more.trajectory_slam.calibration;
  EXPECT_TRUE(m.clock_offset);
  EXPECT_EQ(m.clock_offset_prior_s, 0.5);
  EXPECT_EQ(m.clock_offset_sigma_s, 0.2);
  EXPECT_TRUE(m.compass_deviation);
  EXPECT_EQ(m.compass_deviation_cos_prior_deg, 0.6);
  EXPECT_EQ(m.compass_deviation_sin_prior_deg, -3.0);
  EXPECT_EQ(m.compass_deviation_sigma_deg, 1.0);
  expect_bad_slam_config("trajectory_slam:\n  calibration: {clock_offset_sigma_s: 0}\n", 2,
                         "trajectory_slam.calibration.clock_offset_sigma_s");
  expect_bad_slam_config("trajectory_slam:\n  calibration: {compass_deviation_sin_prior_deg: 50}\n",
                         2, "trajectory_slam.calibration.compass_deviation_sin_prior_deg");
  expect_bad_slam_config("trajectory_slam:\n  calibration: {compass_deviation_sigma_deg: -1}\n", 2,
                         "trajectory_slam.calibration.compass_deviation_sigma_deg");
  expect_bad_slam_config("trajectory_slam:\n  calibration: {range_scale_sigma: 0}\n", 2,
                         "trajectory_slam.calibration.range_scale_sigma");
  EXPECT_FALSE(m.heading_bias);
  EXPECT_EQ(more.dead_reckoning.heading_bias_walk_deg_per_sqrt_s, 0.0);
  EXPECT_EQ(more.dead_reckoning.heading_bias_sigma_deg, 0.0);
  // The compass's bias model is the dead reckoning's; the SLAM's state takes it from there.
  const SlamConfig bias =
      read_slam_config(write_text(dir.file("bias.yaml"),
                                  "dead_reckoning: {heading_bias_walk_deg_per_sqrt_s: 0.05,\n"
                                  "                 heading_bias_sigma_deg: 1.5}\n"
                                  "trajectory_slam:\n"
                                  "  calibration: {heading_bias: true}\n"));
  EXPECT_EQ(bias.dead_reckoning.heading_bias_walk_deg_per_sqrt_s, 0.05);
  EXPECT_EQ(bias.dead_reckoning.heading_bias_sigma_deg, 1.5);
  EXPECT_EQ(bias.dead_reckoning.dvl_scale_sigma, 0.0);
  EXPECT_EQ(read_slam_config(
                write_text(dir.file("scale.yaml"), "dead_reckoning: {dvl_scale_sigma: 0.01}\n"))
                .dead_reckoning.dvl_scale_sigma,
            0.01);
  expect_bad_slam_config("dead_reckoning: {dvl_scale_sigma: 0.5}\n", 1,
                         "dead_reckoning.dvl_scale_sigma");
  EXPECT_TRUE(bias.trajectory_slam.calibration.heading_bias);
  EXPECT_EQ(bias.trajectory_slam.calibration.heading_bias_sigma_deg, 1.5);
  EXPECT_EQ(bias.trajectory_slam.calibration.heading_bias_walk_deg_per_sqrt_s, 0.05);
  expect_bad_slam_config("trajectory_slam:\n  calibration: {heading_bias: true}\n", 2,
                         "trajectory_slam.calibration.heading_bias");
  expect_bad_slam_config("dead_reckoning: {heading_bias_sigma_deg: -1}\n", 1,
                         "dead_reckoning.heading_bias_sigma_deg");
  expect_bad_slam_config("dead_reckoning: {heading_bias_walk_deg_per_sqrt_s: .nan}\n", 1,
                         "dead_reckoning.heading_bias_walk_deg_per_sqrt_s");
  expect_bad_slam_config("trajectory_slam:\n  calibration: {heading_bias_sigma_deg: 1}\n", 2,
                         "trajectory_slam.calibration.heading_bias_sigma_deg");
  expect_bad_slam_config("trajectory_slam:\n  calibration: {range_scale_prior: -1}\n", 2,
                         "trajectory_slam.calibration.range_scale_prior");
  expect_bad_slam_config("trajectory_slam:\n  calibration: {sound_speed: 1}\n", 2,
                         "trajectory_slam.calibration.sound_speed");
}

TEST(SlamConfigYaml, PoseGraphKeys) {
  const TempDir dir;
  const SlamConfig defaults = read_slam_config(write_text(dir.file("d.yaml"), "# defaults\n"));
  EXPECT_EQ(defaults.pose_graph.graph.robust_loss, RobustLoss::kDynamicCovarianceScaling);
  EXPECT_EQ(defaults.pose_graph.solve_every, 1);
  EXPECT_EQ(defaults.pose_graph.online_window_scans, 0);
  EXPECT_EQ(defaults.pose_graph.online_old_nodes, 30);
  EXPECT_EQ(defaults.pose_graph.online_old_chain_scans, 10);
  const SlamConfig c = read_slam_config(write_text(dir.file("slam.yaml"),
                                                   "pose_graph:\n"
                                                   "  robust_loss: cauchy\n"
                                                   "  robust_scale_chi2: 0\n"
                                                   "  robust_start_factor: 1\n"
                                                   "  max_iterations: 20\n"
                                                   "  solve_every: 5\n"
                                                   "  online_window_scans: 100\n"
                                                   "  online_old_nodes: 0\n"
                                                   "  online_old_chain_scans: 3\n"));
  EXPECT_EQ(c.pose_graph.graph.robust_loss, RobustLoss::kCauchy);
  EXPECT_EQ(c.pose_graph.graph.robust_scale_chi2, 0.0);
  EXPECT_EQ(c.pose_graph.graph.robust_start_factor, 1.0);
  EXPECT_EQ(c.pose_graph.graph.max_iterations, 20);
  EXPECT_EQ(c.pose_graph.solve_every, 5);
  EXPECT_EQ(c.pose_graph.online_window_scans, 100);
  EXPECT_EQ(c.pose_graph.online_old_nodes, 0);
  EXPECT_EQ(c.pose_graph.online_old_chain_scans, 3);
  expect_bad_slam_config("pose_graph:\n  online_old_nodes: -1\n", 2, "pose_graph.online_old_nodes");
  expect_bad_slam_config("pose_graph:\n  online_old_chain_scans: 1.5\n", 2,
                         "pose_graph.online_old_chain_scans");
  expect_bad_slam_config("pose_graph:\n  online_window_scans: -1\n", 2,
                         "pose_graph.online_window_scans");
  expect_bad_slam_config("pose_graph:\n  robust_loss: huber\n", 2, "pose_graph.robust_loss");
  expect_bad_slam_config("pose_graph:\n  robust_start_factor: 0.5\n", 2,
                         "pose_graph.robust_start_factor");
  expect_bad_slam_config("pose_graph:\n  solve_every: 0\n", 2, "pose_graph.solve_every");
  expect_bad_slam_config("pose_graph:\n  solve_evry: 2\n", 2, "pose_graph.solve_evry");
}

TEST(SlamConfigYaml, HeadingSigmaDegreesBecomeRadians) {
  const TempDir dir;
  for (const double deg : {0.5, 1.0, 10.0, 180.0}) {
    const std::string text = "dead_reckoning: {heading_sigma_deg: " + std::to_string(deg) + "}\n";
    const SlamConfig c = read_slam_config(write_text(dir.file("slam.yaml"), text));
    EXPECT_NEAR(c.dead_reckoning.heading_sigma_rad, deg * kPi / 180.0, 1e-15) << deg;
    // Only the heading sigma changes.
    EXPECT_EQ(c.dead_reckoning.dvl_sigma_mps, DeadReckoningConfig{}.dvl_sigma_mps);
  }
}

TEST(SlamConfigYaml, SegmentsInFileOrder) {
  const TempDir dir;
  const SlamConfig c = read_slam_config(write_text(dir.file("slam.yaml"),
                                                   "segments:\n"
                                                   "  zeta: [0, 1800]\n"
                                                   "  alpha: [1800, 3300.5]\n"
                                                   "  mid: [-5, 1e3]\n"));
  ASSERT_EQ(c.segments.size(), 3u);
  EXPECT_EQ(c.segments[0].name, "zeta");
  EXPECT_EQ(c.segments[0].begin_s, 0.0);
  EXPECT_EQ(c.segments[0].end_s, 1800.0);
  EXPECT_EQ(c.segments[1].name, "alpha");
  EXPECT_EQ(c.segments[1].begin_s, 1800.0);
  EXPECT_EQ(c.segments[1].end_s, 3300.5);
  EXPECT_EQ(c.segments[2].name, "mid");
  EXPECT_EQ(c.segments[2].begin_s, -5.0);
  EXPECT_EQ(c.segments[2].end_s, 1000.0);
}

TEST(SlamConfigYaml, BadSegments) {
  expect_bad_slam_config("segments:\n  loop: [0, 10]\n  back: [5, 1]\n", 3, "segments.back");
  expect_bad_slam_config("segments:\n  same: [5, 5]\n", 2, "segments.same");
  expect_bad_slam_config("segments:\n  one: [5]\n", 2, "segments.one");
  expect_bad_slam_config("segments:\n  three: [1, 2, 3]\n", 2, "segments.three");
  expect_bad_slam_config("segments:\n  words: all of it\n", 2, "segments.words");
  expect_bad_slam_config("segments:\n  mixed: [0, end]\n", 2, "segments.mixed");
  expect_bad_slam_config("segments:\n  nan: [0, .nan]\n", 2, "segments.nan");
  expect_bad_slam_config("segments: [0, 10]\n", 1, "segments");
  // Names go into CSV and JSON files: letters, digits, '_' and '-' only.
  expect_bad_slam_config("segments:\n  \"a,b\": [0, 10]\n", 2, "segments.a,b");
  expect_bad_slam_config("segments:\n  \"\": [0, 10]\n", 2, "segments.");
}

// BUG (settings/config_yaml.cpp, read_segments, with YamlMap::numbers): a repeated segment name
// gives two segments that both carry the first window; the second window is silently lost.
TEST(SlamConfigYaml, DuplicateSegmentNamesAreRejected) {
  SCOPED_TRACE("BUG: a repeated segment name is accepted with the first window twice");
  expect_bad_slam_config("segments:\n  a: [0, 10]\n  a: [20, 30]\n", 3, "segments.a");
}

// Which sonar data `run` reads: auto by default, raw or detections when named; a typo is an error.
TEST(SlamConfigYaml, SegmentationSource) {
  const TempDir dir;
  EXPECT_EQ(read_slam_config(write_text(dir.file("a.yaml"), "# defaults\n")).segmentation.source,
            SonarSource::kAuto);
  const std::pair<const char*, SonarSource> cases[] = {{"auto", SonarSource::kAuto},
                                                       {"raw", SonarSource::kRaw},
                                                       {"detections", SonarSource::kDetections}};
  for (const auto& [name, source] : cases) {
    const std::string text = std::string("segmentation:\n  source: ") + name + "\n";
    EXPECT_EQ(read_slam_config(write_text(dir.file("s.yaml"), text)).segmentation.source, source)
        << name;
  }
  expect_bad_slam_config("segmentation:\n  source: detection\n", 2, "segmentation.source");
  expect_bad_slam_config("segmentation:\n  source: [raw]\n", 2, "segmentation.source");
}

TEST(SlamConfigYaml, NonPositiveSigmasRejected) {
  for (const std::string key :
       {"dvl_sigma_mps", "heading_sigma_deg", "accel_sigma_mps2", "yaw_accel_sigma_radps2",
        "initial_velocity_sigma_mps", "initial_yaw_rate_sigma_radps"}) {
    SCOPED_TRACE(key);
    expect_bad_slam_config("dead_reckoning:\n  " + key + ": 0\n", 2, "dead_reckoning." + key);
    expect_bad_slam_config("dead_reckoning:\n\n  " + key + ": -1.5\n", 3, "dead_reckoning." + key);
  }
}

TEST(SlamConfigYaml, UnknownAndMistypedKeys) {
  expect_bad_slam_config("dead_reckoning:\n  dvl_sigma: 0.1\n", 2, "dead_reckoning.dvl_sigma");
  expect_bad_slam_config("segment:\n  a: [0, 1]\n", 1, "segment");
  expect_bad_slam_config("dead_reckoning:\n  dvl_sigma_mps: fast\n", 2,
                         "dead_reckoning.dvl_sigma_mps");
  expect_bad_slam_config("dead_reckoning: [1]\n", 1, "dead_reckoning");
}

}  // namespace
}  // namespace msislab::settings
