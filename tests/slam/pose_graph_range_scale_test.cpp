// The pose graph's range scale (trajectory_slam.calibration.range_scale; docs/pose_graph.md, "The
// sonar's range scale"): one scalar block for the graph, its prior, and every match edge through
// it. The new edge's Jacobians against Ceres' numeric ones; on synthetic loops whose scans see the
// world 4 % small, the scale found and the trajectory better than without the block, in the
// whole-graph and the windowed back end (the filters' recovery test, on the graph).
#include <gtest/gtest.h>

#include <cmath>
#include <iostream>
#include <vector>

#include "slam/pose_graph.hpp"
#include "slam/pose_graph_slam.hpp"
#include "tests/slam/residual_jacobian_check.hpp"
#include "tests/slam/synthetic_loop.hpp"

namespace msislab {
namespace {

TEST(PoseGraphRangeScale, EdgeJacobiansMatchCentralDifferences) {
  PoseGraph graph;
  graph.add_node(Pose2(1.0, -2.0, 0.7));
  graph.add_node(Pose2(4.0, 1.5, 2.9));
  EXPECT_THROW(graph.add_scaled_relative(0, 1, {}, Eigen::Matrix3d::Identity(), true),
               std::out_of_range);
  graph.add_range_scale(0.97, 1.0, 0.05);
  EXPECT_THROW(graph.add_range_scale(1.0, 1.0, 0.05), std::invalid_argument);
  GaussianPose2 z{Pose2(3.5, 2.0, 2.0), Eigen::Vector3d(0.04, 0.09, 0.001).asDiagonal()};
  z.cov(0, 1) = z.cov(1, 0) = 0.01;
  graph.add_scaled_relative(0, 1, z, Eigen::Matrix3d::Identity(), true);
  // A match that leaves a direction out (2 orthonormal rows), not robust.
  Eigen::MatrixXd A = Eigen::MatrixXd::Zero(2, 3);
  A(0, 0) = A(0, 1) = std::sqrt(0.5);
  A(1, 2) = 1.0;
  graph.add_scaled_relative(1, 0, z, A, false);
  expect_residual_jacobians_match(graph.problem_for_checks(), 3);  // the prior and two matches
}

/// Ten loops (seeds 1-10) whose scans see the world 0.96 times its size, the graph with the
/// range-scale block against the graph without. The filters' bounds
/// (tests/slam/calibration_states_test.cpp,
/// RecoverTheRangeScaleOfScansThatSeeTheWorld4PercentSmall): the estimate within two of its
/// standard deviations of 0.96 in at least 9 (a consistent estimate: each with probability 0.954, 9
/// or more of 10 with 0.93), the smoothed trajectory's mean error below the graph's without the
/// block in at least 9.
void expect_range_scale_recovered(int window) {
  int within = 0, better = 0;
  PoseGraphSlamConfig graph;
  graph.online_window_scans = window;
  TrajectorySlamConfig with_state;
  with_state.calibration.range_scale = true;
  for (unsigned seed = 1; seed <= 10; ++seed) {
    const Loop loop = scaled(make_loop(seed, false), 0.96);
    PoseGraphSlam estimating(with_state, graph, GaussianPose2{});
    PoseGraphSlam ignoring(TrajectorySlamConfig{}, graph, GaussianPose2{});
    for (const Scan& scan : loop.scans) estimating.add_scan(scan), ignoring.add_scan(scan);
    const auto mean_error_m = [&](const PoseGraphSlam& slam) {
      double sum = 0.0;
      for (std::size_t i = 0; i < slam.scans(); ++i) {
        sum += (slam.scan_pose_world(i).mean.translation() - loop.truth[i].translation()).norm();
      }
      return sum / static_cast<double>(slam.scans());
    };
    const double with_m = mean_error_m(estimating), without_m = mean_error_m(ignoring);
    // Read after the smoothed trajectory, as a run reads it: the smoothed graph's estimate.
    const std::vector<CalibrationEstimate> c = estimating.calibration();
    ASSERT_EQ(c.size(), 1u);
    EXPECT_EQ(c[0].name, "range_scale");
    EXPECT_GT(c[0].sigma, 0.0);
    EXPECT_LT(c[0].sigma, 0.02);  // the loops inform it well below its 0.05 prior
    within += std::abs(c[0].value - 0.96) < 2.0 * c[0].sigma;
    better += with_m < without_m;
    std::cout << "window " << window << ", seed " << seed << ": range scale " << c[0].value
              << " +- " << c[0].sigma << ", mean error " << with_m << " m (without " << without_m
              << " m)\n";
    EXPECT_TRUE(ignoring.calibration().empty());
  }
  EXPECT_GE(within, 9);
  EXPECT_GE(better, 9);
}

TEST(PoseGraphRangeScale, WholeGraphRecoversScansThatSeeTheWorld4PercentSmall) {
  expect_range_scale_recovered(0);
}

TEST(PoseGraphRangeScale, WindowedGraphRecoversScansThatSeeTheWorld4PercentSmall) {
  expect_range_scale_recovered(8);
}

// The same code on a short stretch of one loop, whole graph and windowed, with the heading bias
// leading the parameters too: what the sanitizer build runs (the ten-loop tests above take
// minutes under it). Finite estimates; the scale's sd below its prior's.
TEST(PoseGraphRangeScale, AShortStretchInBothBackEndsWithTheHeadingBias) {
  Loop loop = scaled(make_loop(4, false), 0.96);
  with_walking_compass(loop, 0.3, 0.1, 4);
  TrajectorySlamConfig front = with_heading_bias(0.3);
  front.calibration.range_scale = true;
  for (const int window : {0, 4}) {
    PoseGraphSlamConfig graph;
    graph.online_window_scans = window;
    PoseGraphSlam slam(front, graph, GaussianPose2{});
    for (std::size_t k = 0; k < 30; ++k) slam.add_scan(loop.scans[k]);
    const std::vector<CalibrationEstimate> c = slam.calibration();
    ASSERT_EQ(c.size(), 2u);
    EXPECT_EQ(c[0].name, "range_scale");
    EXPECT_EQ(c[1].name, "heading_bias_deg");
    EXPECT_TRUE(std::isfinite(c[0].value) && std::isfinite(c[1].value)) << window;
    EXPECT_GT(c[0].sigma, 0.0) << window;
    EXPECT_LT(c[0].sigma, 0.05) << window;
    EXPECT_TRUE(slam.scan_pose_world(29).cov.allFinite()) << window;
  }
}

}  // namespace
}  // namespace msislab
