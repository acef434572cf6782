// The vehicle: speed and depth held, turn rate bounded, the path followed to its end.
#include "sim/vehicle.hpp"

#include <gtest/gtest.h>

#include <cmath>

namespace msislab::sim {
namespace {

double distance_to_polyline(const Eigen::Vector2d& p, const std::vector<Eigen::Vector2d>& path) {
  double best = 1e300;
  for (std::size_t i = 1; i < path.size(); ++i) {
    const Eigen::Vector2d leg = path[i] - path[i - 1];
    const double w = std::clamp((p - path[i - 1]).dot(leg) / leg.squaredNorm(), 0.0, 1.0);
    best = std::min(best, (path[i - 1] + w * leg - p).norm());
  }
  return best;
}

/// 50 m due east at 0.5 m/s, from t = 100 s.
VehicleConfig eastward_leg() {
  VehicleConfig config;
  config.speed_mps = 0.5;
  config.start_time_s = 100.0;
  config.path_m = {{0, 0}, {50, 0}};
  return config;
}

TEST(Vehicle, StraightLineAtTheGivenSpeed) {
  const VehicleConfig config = eastward_leg();
  const VehicleTrajectory truth = follow_path(config);
  EXPECT_EQ(truth.start_s(), 100.0);
  EXPECT_NEAR(truth.end_s() - truth.start_s(), 50.0 / 0.5, 2.0);
  EXPECT_NEAR(truth.samples().back().pose.x(), 50.0, 0.6);
  for (const VehicleState& s : truth.samples()) {
    EXPECT_NEAR(s.pose.y(), 0.0, 1e-9);
    EXPECT_EQ(s.surge_mps, 0.5);
  }
  // Interpolation between samples.
  EXPECT_NEAR(truth.at(110.005).pose.x(), 5.0025, 1e-9);
}

TEST(Vehicle, AHeadingHistoryTurnsTheVehicleNotItsPath) {
  // Eastward at 0.5 m/s while pointing north-east, then swinging through north to north-west
  // (across the +-180 deg seam of nothing: 45 -> 135 deg over 50 s): the positions are the
  // course's, the DVL's surge and sway are the world velocity in the turned axes.
  VehicleConfig config = eastward_leg();
  const VehicleTrajectory course = follow_path(config);
  config.heading_deg = {{0.0, 45.0}, {20.0, 45.0}, {70.0, 135.0}};
  const VehicleTrajectory crabbing = follow_path(config);
  ASSERT_EQ(crabbing.samples().size(), course.samples().size());
  for (std::size_t k = 0; k < course.samples().size(); k += 97) {
    const VehicleState& c = course.samples()[k];
    const VehicleState& h = crabbing.samples()[k];
    EXPECT_EQ(h.pose.translation(), c.pose.translation());
    const double t = h.t_s - 100.0;
    const double yaw_deg = t <= 20.0 ? 45.0 : std::min(135.0, 45.0 + 90.0 * (t - 20.0) / 50.0);
    EXPECT_NEAR(h.pose.yaw() * 180.0 / M_PI, yaw_deg, 1e-9) << t;
    const double yaw = h.pose.yaw();
    EXPECT_NEAR(h.surge_mps * std::cos(yaw) - h.sway_mps * std::sin(yaw), 0.5, 1e-9) << t;
    EXPECT_NEAR(h.surge_mps * std::sin(yaw) + h.sway_mps * std::cos(yaw), 0.0, 1e-9) << t;
    if (t > 21.0 && t < 69.0) {
      EXPECT_NEAR(h.yaw_rate_radps, 90.0 / 50.0 * M_PI / 180.0, 1e-9);
    }
    if (t < 19.0) {
      EXPECT_NEAR(h.yaw_rate_radps, 0.0, 1e-12);
    }
  }
  // Across the seam: from 170 deg to -170 deg is 20 deg the short way, not 340.
  const VehicleTrajectory seam = with_heading(course, {{0.0, 170.0}, {100.0, -170.0}});
  EXPECT_NEAR(seam.at(150.0).pose.yaw() * 180.0 / M_PI, 180.0, 1e-6);
}

TEST(Vehicle, LegSpeedsSetTheTimeOfEachLeg) {
  VehicleConfig config;
  config.speed_mps = 1.0;  // unused: every leg has its own speed
  config.path_m = {{0, 0}, {20, 0}, {40, 0}};
  config.leg_speeds_mps = {0.5, 0.1};
  const VehicleTrajectory truth = follow_path(config);
  // 20 m at 0.5 m/s, then 20 m at 0.1 m/s; the end stops up to 0.5 m short of the last waypoint.
  EXPECT_NEAR(truth.at(config.start_time_s + 40.0).pose.x(), 20.0, 0.01);
  EXPECT_NEAR(truth.end_s() - truth.start_s(), 40.0 + 200.0, 5.0);
  EXPECT_EQ(truth.at(config.start_time_s + 10.0).surge_mps, 0.5);
  EXPECT_EQ(truth.at(config.start_time_s + 100.0).surge_mps, 0.1);
}

TEST(Vehicle, SquareLoopStaysNearThePathWithBoundedTurnRate) {
  VehicleConfig config;
  config.speed_mps = 0.3;
  config.path_m = {{0, 0}, {30, 0}, {30, 20}, {0, 20}, {0, 2}};
  const VehicleTrajectory truth = follow_path(config);
  double max_off_m = 0.0;
  for (const VehicleState& s : truth.samples()) {
    EXPECT_LE(std::abs(s.yaw_rate_radps), config.max_turn_rate_radps + 1e-12);
    max_off_m = std::max(max_off_m, distance_to_polyline(s.pose.translation(), config.path_m));
  }
  // Corner cutting by the 3 m carrot: under 1.5 m off the polyline.
  EXPECT_LT(max_off_m, 1.5);
  EXPECT_LT((truth.samples().back().pose.translation() - config.path_m.back()).norm(), 0.6);
  // The heading integrates the yaw rate: successive samples agree with the arc model.
  const auto& s = truth.samples();
  for (std::size_t k = 1; k < s.size(); ++k) {
    EXPECT_NEAR(normalize_angle(s[k].pose.yaw() - s[k - 1].pose.yaw()),
                s[k - 1].yaw_rate_radps * config.step_s, 1e-9);
  }
}

TEST(Vehicle, LoopOverTheSamePlaceDoesNotShortcut) {
  VehicleConfig config;
  config.speed_mps = 0.5;
  // Out and back along the same line, then out again: progress must follow the order.
  config.path_m = {{0, 0}, {20, 0}, {20, 5}, {0, 5}, {0, 0.5}, {20, 0.5}};
  const VehicleTrajectory truth = follow_path(config);
  const double length_m = 20 + 5 + 20 + 4.5 + 20;
  EXPECT_GT(truth.end_s() - truth.start_s(), 0.9 * length_m / config.speed_mps);
  EXPECT_LT((truth.samples().back().pose.translation() - config.path_m.back()).norm(), 0.6);
}

}  // namespace
}  // namespace msislab::sim
