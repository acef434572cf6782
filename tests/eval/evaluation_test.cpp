// Trajectory scoring: interpolation, error statistics, segments and pose NEES.
#include "eval/evaluation.hpp"

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

TEST(Evaluation, InterpolatesPositionsAndHoldsTheEndsOutsideTheTrack) {
  const std::vector<PositionFix> track = {{0.0, {0.0, 0.0}}, {2.0, {4.0, -2.0}}};
  EXPECT_TRUE(interpolate_position(track, 0.5).isApprox(Eigen::Vector2d(1.0, -0.5)));
  EXPECT_EQ(interpolate_position(track, -1.0), track.front().p_world_m);
  EXPECT_EQ(interpolate_position(track, 3.0), track.back().p_world_m);
}

TEST(Evaluation, MatchTranslationScaleProjectsOnTheTrueDisplacementInTheReferenceFrame) {
  // Truth: a vehicle heading north-east at 1 m/s; fixes every 2 s with one 10 s gap (t 40..50).
  const double heading_rad = M_PI / 4.0;
  const Eigen::Vector2d direction(std::cos(heading_rad), std::sin(heading_rad));
  std::vector<PositionFix> truth;
  for (double t = 0.0; t <= 40.0; t += 2.0) truth.push_back({t, t * direction});
  for (double t = 50.0; t <= 80.0; t += 2.0) truth.push_back({t, t * direction});
  // Matches 3 s apart (3 m), the scan's translation 0.9 of it along the vehicle's x, plus a
  // sideways error that the projection must ignore.
  std::vector<MatchTranslation> matches;
  for (double t = 1.0; t + 3.0 <= 38.0; t += 3.0) {
    matches.push_back({t, t + 3.0, heading_rad, Eigen::Vector2d(2.7, t < 20.0 ? 0.5 : -0.5)});
  }
  const std::optional<double> scale = match_translation_scale(matches, truth);
  ASSERT_TRUE(scale.has_value());
  EXPECT_NEAR(*scale, 0.9, 1e-12);

  // A match across the fix gap, one shorter than the minimum and one outside the truth are left
  // out: the figure is unchanged.
  std::vector<MatchTranslation> with_skipped = matches;
  with_skipped.push_back({39.0, 42.0, heading_rad, Eigen::Vector2d(30.0, 0.0)});
  with_skipped.push_back({60.0, 60.5, heading_rad, Eigen::Vector2d(30.0, 0.0)});
  with_skipped.push_back({79.0, 82.0, heading_rad, Eigen::Vector2d(30.0, 0.0)});
  EXPECT_NEAR(*match_translation_scale(with_skipped, truth), 0.9, 1e-12);

  // The reference yaw matters: the same translation read with a yaw 90 deg off is orthogonal to
  // the true displacement.
  std::vector<MatchTranslation> turned = matches;
  for (MatchTranslation& m : turned) {
    m.yaw_reference_rad += M_PI / 2.0;
    m.translation_reference_m.y() = 0.0;
  }
  EXPECT_NEAR(*match_translation_scale(turned, truth), 0.0, 1e-12);

  EXPECT_FALSE(match_translation_scale({}, truth).has_value());
  EXPECT_FALSE(match_translation_scale({{60.0, 60.5, 0.0, Eigen::Vector2d(1, 0)}}, truth));
}

}  // namespace
}  // namespace msislab
