// The vehicle: speed and depth held, turn rate bounded, the path followed to its end.
#include "sim/vehicle.hpp"

#include <gtest/gtest.h>

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

TEST(Vehicle, StraightLineAtTheGivenSpeed) {
  VehicleConfig config;
  config.speed_mps = 0.5;
  config.start_time_s = 100.0;
  config.path_m = {{0, 0}, {50, 0}};
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
