// Trajectory scoring: interpolation, error statistics, segments and pose NEES.
#include "slam/evaluation.hpp"

#include <gtest/gtest.h>

#include <cmath>

namespace msislab {
namespace {

std::vector<StampedPose> line_trajectory() {
  // x = t along the x axis from t = 0 to 10 s, sampled every second.
  std::vector<StampedPose> out;
  for (int i = 0; i <= 10; ++i) out.push_back({double(i), {Pose2(i, 0.0, 0.0)}});
  return out;
}

TEST(Evaluation, InterpolatesPositionAndYawAcrossTheWrap) {
  std::vector<StampedPose> traj = {{0.0, {Pose2(0, 0, M_PI - 0.1)}},
                                   {1.0, {Pose2(2, 4, -M_PI + 0.1)}}};
  const Pose2 mid = interpolate_pose(traj, 0.5);
  EXPECT_NEAR(mid.x(), 1.0, 1e-12);
  EXPECT_NEAR(mid.y(), 2.0, 1e-12);
  EXPECT_NEAR(std::abs(mid.yaw()), M_PI, 1e-12);  // the short way through pi, not through 0
  EXPECT_NEAR(interpolate_pose(traj, 0.0).yaw(), M_PI - 0.1, 1e-12);
  EXPECT_NEAR(interpolate_pose(traj, 1.0).x(), 2.0, 1e-12);
}

TEST(Evaluation, ErrorsOnlyInsideTheEstimatedSpan) {
  const std::vector<PositionFix> truth = {
      {-1.0, {-1, 0}}, {0.5, {0.5, 3}}, {2.0, {2, -4}}, {9.5, {9.5, 0}}, {11.0, {11, 0}}};
  const auto errors = position_errors(line_trajectory(), truth);
  ASSERT_EQ(errors.size(), 3u);
  EXPECT_NEAR(errors[0].error_m, 3.0, 1e-12);
  EXPECT_NEAR(errors[1].error_m, 4.0, 1e-12);
  EXPECT_NEAR(errors[2].error_m, 0.0, 1e-12);
}

TEST(Evaluation, StatisticsOfKnownErrors) {
  const std::vector<ErrorSample> errors = {{0, 3.0}, {1, 1.0}, {2, 4.0}, {3, 2.0}};
  const auto stats = error_stats(errors);
  ASSERT_TRUE(stats);
  EXPECT_EQ(stats->count, 4u);
  EXPECT_DOUBLE_EQ(stats->mean_m, 2.5);
  EXPECT_DOUBLE_EQ(stats->median_m, 2.5);
  EXPECT_DOUBLE_EQ(stats->max_m, 4.0);
  EXPECT_DOUBLE_EQ(stats->final_m, 2.0);
  EXPECT_DOUBLE_EQ(stats->rmse_m, std::sqrt((9.0 + 1.0 + 16.0 + 4.0) / 4.0));
  EXPECT_FALSE(error_stats({}));
}

TEST(Evaluation, SegmentMeansUseTimeFromTheFirstTruthStamp) {
  const std::vector<ErrorSample> errors = {{100, 1.0}, {101, 3.0}, {102, 10.0}, {103, 20.0}};
  EXPECT_DOUBLE_EQ(*segment_mean_error(errors, 100.0, {"a", 0.0, 2.0}), 2.0);
  EXPECT_DOUBLE_EQ(*segment_mean_error(errors, 100.0, {"b", 2.0, 10.0}), 15.0);
  EXPECT_FALSE(segment_mean_error(errors, 100.0, {"c", 50.0, 60.0}));
}

TEST(Evaluation, PoseNeesAgainstInterpolatedTruthWithWrappedAngle) {
  // Truth along x at 1 m/s with yaw pi - 0.05; the estimate at t = 2.5 s is off by (0.3, -0.4) m
  // and by +0.1 rad, which wraps through pi.
  std::vector<StampedPose> truth;
  for (int i = 0; i <= 5; ++i) truth.push_back({double(i), {Pose2(i, 0.0, M_PI - 0.05)}});
  StampedPose estimate{2.5, {Pose2(2.8, -0.4, M_PI + 0.05)}};
  estimate.pose.cov << 0.09, 0.0, 0.0, 0.0, 0.04, 0.0, 0.0, 0.0, 0.01;
  // By hand: (0.3^2 / 0.09) + (0.4^2 / 0.04) + (0.1^2 / 0.01) = 1 + 4 + 1.
  const std::vector<double> nees = pose_nees({estimate}, truth);
  ASSERT_EQ(nees.size(), 1u);
  EXPECT_NEAR(nees[0], 6.0, 1e-9);

  // Correlated covariance: e^T P^-1 e with P^-1 by hand. Only the upper triangle is read.
  estimate.pose.mean = Pose2(2.5 + 1.0, 1.0, M_PI - 0.05);
  estimate.pose.cov << 2.0, 1.0, 0.0, 999.0, 2.0, 0.0, 0.0, 0.0, 1.0;
  // P_xy = [[2, 1], [1, 2]], P_xy^-1 = [[2, -1], [-1, 2]] / 3; e = (1, 1, 0): (2 - 2 + 2) / 3.
  EXPECT_NEAR(pose_nees({estimate}, truth)[0], 2.0 / 3.0, 1e-12);
}

TEST(Evaluation, MeanOfValues) {
  EXPECT_FALSE(mean_of({}));
  EXPECT_DOUBLE_EQ(*mean_of({1.0, 2.0, 6.0}), 3.0);
}

}  // namespace
}  // namespace msislab
