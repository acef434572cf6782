// navigation_noise.yaml and the config a run on a dataset uses: the exact write -> read round trip,
// bad values rejected with "FILE:LINE: key", and the layering: the config file's keys over the
// dataset's noise (only when the config asks, `navigation_noise: dataset`) over the defaults.
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "geometry/angles.hpp"
#include "io/input_error.hpp"
#include "settings/config_yaml.hpp"
#include "test_support.hpp"

namespace msislab::settings {
namespace {

using testing::TempDir;
using testing::write_text;

NavigationNoise sensors() {
  NavigationNoise noise;
  noise.dvl_sigma_mps = 0.20575956842878534;
  noise.heading_sigma_deg = 0.04;
  noise.heading_bias_walk_deg_per_sqrt_s = 0.01;
  noise.heading_bias_sigma_deg = 0.5;
  noise.dvl_scale_sigma = 0.010000000000000009;
  return noise;
}

TEST(NavigationNoiseYaml, RoundTripsExactly) {
  const TempDir dir;
  const std::string path = dir.file("navigation_noise.yaml");
  write_navigation_noise(path, sensors());
  for (const NavigationNoise& n :
       {read_navigation_noise(path), navigation_noise_as_stored(sensors())}) {
    EXPECT_EQ(n.dvl_sigma_mps, sensors().dvl_sigma_mps);
    EXPECT_EQ(n.heading_sigma_deg, sensors().heading_sigma_deg);
    EXPECT_EQ(n.heading_bias_walk_deg_per_sqrt_s, sensors().heading_bias_walk_deg_per_sqrt_s);
    EXPECT_EQ(n.heading_bias_sigma_deg, sensors().heading_bias_sigma_deg);
    EXPECT_EQ(n.dvl_scale_sigma, sensors().dvl_scale_sigma);
  }
}

void expect_bad_noise(const std::string& text, const std::string& where) {
  const TempDir dir;
  const std::string path = write_text(dir.file("navigation_noise.yaml"), text);
  try {
    read_navigation_noise(path);
    ADD_FAILURE() << "no InputError for:\n" << text;
  } catch (const io::InputError& e) {
    EXPECT_NE(std::string(e.what()).find(path + ":" + where), std::string::npos) << e.what();
  }
}

TEST(NavigationNoiseYaml, RejectsBadValuesNamingTheLineAndKey) {
  expect_bad_noise("dead_reckoning:\n  dvl_sigma_mps: -0.1\n",
                   "2: key 'dead_reckoning.dvl_sigma_mps'");
  expect_bad_noise("dead_reckoning:\n  heading_sigma_deg: .nan\n",
                   "2: key 'dead_reckoning.heading_sigma_deg'");
  expect_bad_noise("dead_reckoning:\n  dvl_scale_sigma: 0.5\n",
                   "2: key 'dead_reckoning.dvl_scale_sigma'");
  expect_bad_noise("dead_reckoning:\n  accel_sigma_mps2: 0.1\n",
                   "2: key 'dead_reckoning.accel_sigma_mps2'");
  expect_bad_noise("dvl: {}\n", "1: key 'dvl'");
}

DatasetConfig config_for(const std::string& text, const std::optional<NavigationNoise>& noise) {
  const TempDir dir;
  return slam_config_for_dataset(write_text(dir.file("slam.yaml"), text), noise, "the dataset");
}

TEST(SlamConfigForDataset, WithoutNoiseOrWithoutAskingTheDefaultsStandAndTheNoteSaysHow) {
  const SlamConfig defaults;
  for (const std::optional<NavigationNoise>& noise :
       {std::optional<NavigationNoise>(), std::optional<NavigationNoise>(sensors())}) {
    const DatasetConfig c = config_for("# defaults\n", noise);
    EXPECT_EQ(c.config.dead_reckoning.dvl_sigma_mps, defaults.dead_reckoning.dvl_sigma_mps);
    EXPECT_EQ(c.config.dead_reckoning.heading_sigma_rad, defaults.dead_reckoning.heading_sigma_rad);
    EXPECT_EQ(c.config.dead_reckoning.heading_bias_walk_deg_per_sqrt_s, 0.0);
    EXPECT_FALSE(c.config.trajectory_slam.calibration.heading_bias);
    // Told which values its sensors have and how to use them, when the dataset states them.
    EXPECT_EQ(c.noise_note.find("navigation_noise: dataset") != std::string::npos,
              noise.has_value())
        << c.noise_note;
  }
  // No config file at all: the same.
  const DatasetConfig none = slam_config_for_dataset("", sensors(), "the dataset");
  EXPECT_EQ(none.config.dead_reckoning.dvl_sigma_mps, defaults.dead_reckoning.dvl_sigma_mps);
}

TEST(SlamConfigForDataset, AskedTheConfigsKeysWinOverTheDatasetsOverTheDefaults) {
  const DatasetConfig c =
      config_for("navigation_noise: dataset\ndead_reckoning:\n  dvl_sigma_mps: 0.3\n", sensors());
  const DeadReckoningConfig& dr = c.config.dead_reckoning;
  EXPECT_EQ(dr.dvl_sigma_mps, 0.3);  // the config's
  EXPECT_DOUBLE_EQ(dr.heading_sigma_rad, 0.04 * kDegToRad);
  EXPECT_EQ(dr.heading_bias_walk_deg_per_sqrt_s, 0.01);
  EXPECT_EQ(dr.heading_bias_sigma_deg, 0.5);
  EXPECT_EQ(dr.dvl_scale_sigma, sensors().dvl_scale_sigma);
  EXPECT_EQ(dr.accel_sigma_mps2, DeadReckoningConfig{}.accel_sigma_mps2);  // not noise: default
  // The filters model what the dead reckoning does: the heading-bias state follows the model.
  const CalibrationStatesConfig& states = c.config.trajectory_slam.calibration;
  EXPECT_TRUE(states.heading_bias);
  EXPECT_EQ(states.heading_bias_walk_deg_per_sqrt_s, 0.01);
  EXPECT_EQ(states.heading_bias_sigma_deg, 0.5);
  EXPECT_NE(c.noise_note.find("heading_sigma_deg 0.04"), std::string::npos) << c.noise_note;
  EXPECT_EQ(c.noise_note.find("dvl_sigma_mps"), std::string::npos) << c.noise_note;
  // Said off, the state stays off.
  EXPECT_FALSE(config_for("navigation_noise: dataset\ntrajectory_slam:\n  calibration: "
                          "{heading_bias: false}\n",
                          sensors())
                   .config.trajectory_slam.calibration.heading_bias);
}

TEST(SlamConfigForDataset, AWhiteNoiseOfZeroIsNotTakenAndABadChoiceIsAnError) {
  NavigationNoise exact = sensors();
  exact.dvl_sigma_mps = 0.0;
  exact.heading_sigma_deg = 0.0;
  const DatasetConfig c = config_for("navigation_noise: dataset\n", exact);
  EXPECT_EQ(c.config.dead_reckoning.dvl_sigma_mps, DeadReckoningConfig{}.dvl_sigma_mps);
  EXPECT_EQ(c.config.dead_reckoning.heading_sigma_rad, DeadReckoningConfig{}.heading_sigma_rad);
  EXPECT_EQ(c.config.dead_reckoning.heading_bias_walk_deg_per_sqrt_s, 0.01);
  const TempDir dir;
  const std::string path = write_text(dir.file("slam.yaml"), "navigation_noise: scenario\n");
  try {
    slam_config_for_dataset(path, sensors(), "the dataset");
    ADD_FAILURE() << "no InputError";
  } catch (const io::InputError& e) {
    EXPECT_NE(std::string(e.what()).find(path + ":1: key 'navigation_noise'"), std::string::npos)
        << e.what();
  }
}

}  // namespace
}  // namespace msislab::settings
