// The scan-match scale on a straight wall pair (docs/simulator.md, "Echo shape"): the straight
// channel simulated with the St. Pere replica's echo (500 us box pulse, no receiver tail, the
// publisher's detector with a 23-bin window), read through the detections with the default SLAM
// config. With a narrow beam the consecutive matches measure the motion within 2 % (measured
// 0.988 with a 1 deg beam); the replica's 6 deg beam shortens them (0.969): across a wide beam a
// wall's range d / cos(incidence) is convex in the angle, so at grazing incidence the centre of
// the detected run lies behind the axis's hit, more the more oblique the wall, and the walls of
// the channel bow outward around the sonar.
#include <gtest/gtest.h>

#include <iostream>
#include <limits>
#include <optional>
#include <string>

#include "app/run_command.hpp"
#include "app/simulate_command.hpp"
#include "test_support.hpp"

namespace msislab::app {
namespace {

double match_scale(const testing::TempDir& tmp, const std::string& name, double beamwidth_deg) {
  std::string yaml =
      testing::read_text(std::string(MSISLAB_SOURCE_DIR) + "/scenarios/straight_channel.yaml");
  const std::string mesh = "mesh: ../scenes/straight_channel.obj";
  const std::string sonar = "sonar: {}";
  const auto at_mesh = yaml.find(mesh);
  const auto at_sonar = yaml.find(sonar);
  if (at_mesh == std::string::npos || at_sonar == std::string::npos) {
    ADD_FAILURE() << "scenarios/straight_channel.yaml changed its mesh or sonar line";
    return std::numeric_limits<double>::quiet_NaN();
  }
  yaml.replace(at_sonar, sonar.size(),
               "sonar: {pulse_length_us: 500, receiver_time_constant_us: 0, "
               "horizontal_beamwidth_deg: " +
                   std::to_string(beamwidth_deg) +
                   ", horizontal_span_beamwidths: 2.5, rays_horizontal: 24}\n"
                   "detections: {smoothing_bins: 23}");
  yaml.replace(at_mesh, mesh.size(),
               "mesh: " + std::string(MSISLAB_SOURCE_DIR) + "/scenes/straight_channel.obj");
  const std::string scenario = testing::write_text(tmp.file(name + ".yaml"), yaml);
  simulate({scenario, tmp.file(name), std::nullopt, 2});
  const RunOutcome rc = run({tmp.file(name), "robocentric", tmp.file(name + "_rc"), ""});
  if (!rc.metrics) {
    ADD_FAILURE() << name << ": no metrics";
    return std::numeric_limits<double>::quiet_NaN();
  }
  for (const auto& [key, value] : rc.metrics->diagnostics) {
    if (key == "consecutive_match_scale") {
      std::cout << name << ": consecutive_match_scale " << value << ", mean error "
                << rc.metrics->errors.mean_m << " m\n";
      return value;
    }
  }
  ADD_FAILURE() << name << ": no consecutive_match_scale";
  return std::numeric_limits<double>::quiet_NaN();
}

TEST(MatchScale, NarrowBeamMeasuresTheMotionAndTheWideBeamShortensIt) {
  const testing::TempDir tmp;
  const double narrow = match_scale(tmp, "narrow", 1.0);
  const double wide = match_scale(tmp, "wide", 6.0);
  EXPECT_NEAR(narrow, 1.0, 0.02);  // 0.988
  EXPECT_LT(wide, narrow - 0.01);  // 0.969
  EXPECT_GT(wide, 0.94);
}

}  // namespace
}  // namespace msislab::app
