// The config an external method is given (settings/external_config): both writers' files read
// back with read_slam_config() to every dead_reckoning value written, none left at its default;
// the resolved copy keeps the file's other keys and says `navigation_noise: config`.
#include "settings/external_config.hpp"

#include <gtest/gtest.h>

#include <string>

#include "geometry/angles.hpp"
#include "settings/config_yaml.hpp"
#include "test_support.hpp"

namespace msislab::settings {
namespace {

using testing::TempDir;
using testing::write_text;

/// Every dead_reckoning value away from its default (and representable in decimal).
DeadReckoningConfig unusual() {
  DeadReckoningConfig c;
  c.dvl_sigma_mps = 0.0125;
  c.heading_sigma_rad = 0.3 * kDegToRad;
  c.accel_sigma_mps2 = 0.07;
  c.yaw_accel_sigma_radps2 = 0.011;
  c.initial_velocity_sigma_mps = 0.45;
  c.initial_yaw_rate_sigma_radps = 0.06;
  c.dvl_gate_chi2 = 13.5;
  c.heading_bias_walk_deg_per_sqrt_s = 0.02;
  c.heading_bias_sigma_deg = 0.7;
  c.dvl_scale_sigma = 0.015;
  return c;
}

void expect_same(const DeadReckoningConfig& read, const DeadReckoningConfig& written) {
  EXPECT_DOUBLE_EQ(read.dvl_sigma_mps, written.dvl_sigma_mps);
  EXPECT_NEAR(read.heading_sigma_rad, written.heading_sigma_rad, 1e-15);
  EXPECT_DOUBLE_EQ(read.accel_sigma_mps2, written.accel_sigma_mps2);
  EXPECT_DOUBLE_EQ(read.yaw_accel_sigma_radps2, written.yaw_accel_sigma_radps2);
  EXPECT_DOUBLE_EQ(read.initial_velocity_sigma_mps, written.initial_velocity_sigma_mps);
  EXPECT_DOUBLE_EQ(read.initial_yaw_rate_sigma_radps, written.initial_yaw_rate_sigma_radps);
  EXPECT_DOUBLE_EQ(read.dvl_gate_chi2, written.dvl_gate_chi2);
  EXPECT_DOUBLE_EQ(read.heading_bias_walk_deg_per_sqrt_s, written.heading_bias_walk_deg_per_sqrt_s);
  EXPECT_DOUBLE_EQ(read.heading_bias_sigma_deg, written.heading_bias_sigma_deg);
  EXPECT_DOUBLE_EQ(read.dvl_scale_sigma, written.dvl_scale_sigma);
}

TEST(ExternalConfig, TheDeadReckoningSectionReadsBackWhole) {
  const TempDir dir;
  const std::string path = dir.file("config.yaml");
  write_dead_reckoning_config(path, unusual());
  expect_same(read_slam_config(path).dead_reckoning, unusual());
}

TEST(ExternalConfig, TheResolvedCopyKeepsTheFilesOtherKeys) {
  const TempDir dir;
  const std::string own = write_text(dir.file("own.yaml"),
                                     "# a user's config\nnavigation_noise: dataset\n"
                                     "dead_reckoning:\n  dvl_sigma_mps: 0.3\n"
                                     "trajectory_slam:\n  max_matches_per_scan: 2\n");
  const std::string path = dir.file("resolved.yaml");
  write_resolved_config(path, own, unusual());
  const SlamConfig read = read_slam_config(path);
  EXPECT_FALSE(read.navigation_noise_from_dataset);
  expect_same(read.dead_reckoning, unusual());
  EXPECT_EQ(read.trajectory_slam.front_end.max_matches_per_scan, 2);
}

}  // namespace
}  // namespace msislab::settings
