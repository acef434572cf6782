// Relative pose error: a small trajectory computed by hand; pairs by travelled truth path, not by
// displacement; unchanged by a rigid motion of the estimate; no pair when the path is too short.
#include "eval/relative_pose_error.hpp"

#include <gtest/gtest.h>

#include <cmath>

namespace msislab {
namespace {

std::vector<StampedPose> stamped(const std::vector<Pose2>& poses, double t0_s = 0.0) {
  std::vector<StampedPose> out;
  for (std::size_t k = 0; k < poses.size(); ++k) {
    out.push_back({t0_s + static_cast<double>(k), {poses[k]}});
  }
  return out;
}

TEST(RelativePoseError, SmallTrajectoryByHand) {
  // Truth along x at 1 m/s, stamps 0..3 s, plus stamps outside the estimate's span (left out).
  std::vector<StampedPose> truth = stamped({Pose2(-1, 0, 0), Pose2(0, 0, 0), Pose2(1, 0, 0),
                                            Pose2(2, 0, 0), Pose2(3, 0, 0), Pose2(4, 0, 0)},
                                           -1.0);
  const std::vector<StampedPose> estimate = stamped(
      {Pose2(0, 0, 0), Pose2(1, 0, M_PI / 2), Pose2(1, 1, M_PI / 2), Pose2(1, 2, M_PI / 2)});
  const RelativePoseError rpe = relative_pose_error(estimate, truth, 2.0);
  // delta 2 m: pairs (0, 2) and (1, 3) (truth path exactly 2 m).
  // (0, 2): est_02 = (1, 1, 90 deg), true_02 = (2, 0, 0); est_02^-1 = (-1, 1, -90 deg);
  //         E = (-1, 1) + R(-90 deg) (2, 0) = (-1, -1), yaw -90 deg: sqrt(2) m, 90 deg.
  // (1, 3): est_13 = R(90 deg)^T (0, 2) = (2, 0), yaw 0 = true_13: E = 0.
  ASSERT_EQ(rpe.pairs, 2u);
  EXPECT_EQ(rpe.delta_m, 2.0);
  EXPECT_NEAR(rpe.translation_m.mean, std::sqrt(2.0) / 2.0, 1e-12);
  EXPECT_NEAR(rpe.translation_m.rmse, 1.0, 1e-12);  // sqrt((2 + 0) / 2)
  EXPECT_NEAR(rpe.translation_m.median, std::sqrt(2.0) / 2.0, 1e-12);
  EXPECT_NEAR(rpe.translation_m.max, std::sqrt(2.0), 1e-12);
  EXPECT_NEAR(rpe.rotation_deg.mean, 45.0, 1e-9);
  EXPECT_NEAR(rpe.rotation_deg.rmse, std::sqrt(90.0 * 90.0 / 2.0), 1e-9);
  EXPECT_NEAR(rpe.rotation_deg.median, 45.0, 1e-9);
  EXPECT_NEAR(rpe.rotation_deg.max, 90.0, 1e-9);
  // delta 3 m: the one pair (0, 3): est_03 = (1, 2, 90 deg), true_03 = (3, 0, 0);
  // E = (-2, 1) + R(-90 deg) (3, 0) = (-2, -2), yaw -90 deg: 2 sqrt(2) m, 90 deg.
  const RelativePoseError rpe3 = relative_pose_error(estimate, truth, 3.0);
  ASSERT_EQ(rpe3.pairs, 1u);
  EXPECT_NEAR(rpe3.translation_m.max, 2.0 * std::sqrt(2.0), 1e-12);
  EXPECT_NEAR(rpe3.rotation_deg.max, 90.0, 1e-9);
  // A path shorter than delta inside the span: no pair.
  EXPECT_EQ(relative_pose_error(estimate, truth, 3.5).pairs, 0u);
}

TEST(RelativePoseError, EstimateInterpolatedAtTheTruthStamps) {
  // The estimate sampled every 2 s along the truth's line: interpolated at the odd truth stamps
  // it is exact, so the error is zero.
  const std::vector<StampedPose> truth =
      stamped({Pose2(0, 0, 0), Pose2(1, 0, 0), Pose2(2, 0, 0), Pose2(3, 0, 0), Pose2(4, 0, 0)});
  const std::vector<StampedPose> estimate = {
      {0.0, {Pose2(0, 0, 0)}}, {2.0, {Pose2(2, 0, 0)}}, {4.0, {Pose2(4, 0, 0)}}};
  const RelativePoseError rpe = relative_pose_error(estimate, truth, 1.0);
  EXPECT_EQ(rpe.pairs, 4u);
  EXPECT_NEAR(rpe.translation_m.max, 0.0, 1e-12);
}

TEST(RelativePoseError, PairsByTravelledPathNotByDisplacement) {
  // Out 2 m and back: the samples 4 m of path apart are at the same place.
  const std::vector<StampedPose> truth = stamped(
      {Pose2(0, 0, 0), Pose2(1, 0, 0), Pose2(2, 0, 0), Pose2(1, 0, M_PI), Pose2(0, 0, M_PI)});
  // The estimate comes back 0.5 m short.
  std::vector<StampedPose> estimate = truth;
  estimate[4].pose.mean = Pose2(0.5, 0, M_PI);
  const RelativePoseError rpe = relative_pose_error(estimate, truth, 4.0);
  ASSERT_EQ(rpe.pairs, 1u);
  EXPECT_NEAR(rpe.translation_m.max, 0.5, 1e-12);
  EXPECT_NEAR(rpe.rotation_deg.max, 0.0, 1e-9);
}

TEST(RelativePoseError, UnchangedByARigidMotionOfTheEstimate) {
  std::vector<StampedPose> truth, estimate;
  for (int k = 0; k <= 200; ++k) {
    const double t_s = 0.1 * k;
    truth.push_back({t_s, {Pose2(t_s, std::sin(t_s), 0.3 * t_s)}});
    estimate.push_back({t_s, {Pose2(1.01 * t_s, std::sin(t_s) + 0.01 * t_s, 0.31 * t_s)}});
  }
  const RelativePoseError rpe = relative_pose_error(estimate, truth, 5.0);
  ASSERT_GT(rpe.pairs, 50u);
  EXPECT_GT(rpe.translation_m.mean, 0.01);
  const Pose2 T(30.0, -7.0, 2.5);
  std::vector<StampedPose> moved = estimate;
  for (StampedPose& p : moved) p.pose.mean = T + p.pose.mean;
  const RelativePoseError rpe_moved = relative_pose_error(moved, truth, 5.0);
  EXPECT_EQ(rpe_moved.pairs, rpe.pairs);
  EXPECT_NEAR(rpe_moved.translation_m.mean, rpe.translation_m.mean, 1e-9);
  EXPECT_NEAR(rpe_moved.rotation_deg.max, rpe.rotation_deg.max, 1e-9);
  // And the truth against itself has none.
  EXPECT_NEAR(relative_pose_error(truth, truth, 5.0).translation_m.max, 0.0, 1e-12);
}

}  // namespace
}  // namespace msislab
