// The pose graph's heading bias (trajectory_slam.calibration.heading_bias; docs/pose_graph.md,
// "The compass's bias"): a scalar block per scan node, the compass edge through it and the walk
// between neighbours. The new edges' Jacobians against Ceres' numeric ones; on the synthetic loop
// with a compass whose bias walks, the smoothed last yaw consistent and the bias found, in the
// whole-graph and the windowed back end, where the same compass read as white noise is far
// overconfident; switched off, no estimate.
#include <gtest/gtest.h>

#include <cmath>
#include <iostream>
#include <string>

#include "geometry/angles.hpp"
#include "slam/pose_graph.hpp"
#include "slam/pose_graph_slam.hpp"
#include "test_support.hpp"
#include "tests/slam/residual_jacobian_check.hpp"
#include "tests/slam/synthetic_loop.hpp"

namespace msislab {
namespace {

TEST(PoseGraphHeadingBias, EdgeJacobiansMatchCentralDifferences) {
  PoseGraph graph;
  graph.add_node(Pose2(1.0, -2.0, 0.7));
  graph.add_node(Pose2(4.0, 1.5, 2.9));
  graph.add_heading_bias(0, 0.01, false);
  graph.add_heading_bias(1, -0.02, false);
  graph.add_heading_bias_prior(0, 0.003, 0.01);
  graph.add_heading_bias_walk(0, 1, 0.002);
  graph.add_biased_heading(1, 1, 2.5, 0.05);
  graph.add_biased_heading(0, 1, 0.6, 0.05);  // through another node's (a constant) bias
  expect_residual_jacobians_match(graph.problem_for_checks(), 4);
  EXPECT_THROW(graph.add_heading_bias(0, 0.0, false), std::invalid_argument);
  graph.add_node(Pose2());
  EXPECT_THROW(graph.add_biased_heading(2, 2, 0.0, 0.05), std::out_of_range);
}

/// Ten loops with a compass whose bias walks 0.3 deg / sqrt(s) under 0.1 deg of white noise. The
/// bounds are the filters' test's (tests/slam/calibration_states_test.cpp,
/// RecoverTheHeadingBiasOfAWalkingCompass): the smoothed last yaw's 1-DOF NEES averaged over the
/// ten loops inside the two-sided 99 % bounds of chi-square(10) / 10, [0.22, 2.52]; without the
/// state far above (10); the bias within 2 sd in at least 8 of 10.
void expect_walking_compass_recovered(int window) {
  struct {
    double nees_with = 0.0, nees_without = 0.0;
    int within = 0;
  } out;
  PoseGraphSlamConfig graph;
  graph.online_window_scans = window;
  for (unsigned seed = 1; seed <= 10; ++seed) {
    Loop loop = make_loop(testing::seed(seed), false);
    const double bias_rad = with_walking_compass(loop, 0.3, 0.1, testing::seed(seed));
    const TrajectorySlamConfig with_bias = with_heading_bias(0.3);
    PoseGraphSlam estimating(with_bias.front_end, with_bias.calibration, graph, GaussianPose2{});
    PoseGraphSlam ignoring(ScanFrontEndConfig{}, CalibrationStatesConfig{}, graph, GaussianPose2{});
    for (const Scan& scan : loop.scans) estimating.add_scan(scan), ignoring.add_scan(scan);
    estimating.finish(), ignoring.finish();
    const std::size_t last = loop.scans.size() - 1;
    const auto yaw_nees = [&](const PoseGraphSlam& slam) {
      const GaussianPose2 pose = slam.scan_pose_world(last);
      const double e = normalize_angle(pose.mean.yaw() - loop.truth[last].yaw());
      return e * e / pose.cov(2, 2);
    };
    out.nees_with += yaw_nees(estimating) / 10.0;
    out.nees_without += yaw_nees(ignoring) / 10.0;
    const std::vector<CalibrationEstimate> c = estimating.calibration();
    EXPECT_EQ(c.size(), 1u);
    EXPECT_EQ(c.at(0).name, "heading_bias_deg");
    out.within += std::abs(c[0].value - bias_rad / kDegToRad) < 2.0 * c[0].sigma;
    std::cout << "window " << window << ", seed " << seed << ": bias " << bias_rad / kDegToRad
              << " deg, estimated " << c[0].value << " +- " << c[0].sigma << "\n";
    EXPECT_TRUE(ignoring.calibration().empty());
  }
  std::cout << "window " << window << ": last scan's yaw NEES, 10 loops: " << out.nees_with
            << " with the state, " << out.nees_without << " without\n";
  EXPECT_GT(out.nees_with, 0.22);
  EXPECT_LT(out.nees_with, 2.52);
  EXPECT_GT(out.nees_without, 10.0);
  EXPECT_GE(out.within, 8);
}

TEST(PoseGraphHeadingBias, WholeGraphRecoversAWalkingCompassesBias) {
  expect_walking_compass_recovered(0);
}

TEST(PoseGraphHeadingBias, WindowedGraphRecoversAWalkingCompassesBias) {
  expect_walking_compass_recovered(8);
}

// The same code on a short stretch of one loop, whole graph and windowed: what the sanitizer build
// runs (the ten-loop tests above take minutes under it; CMakePresets.json, docs/reliability.md).
// The estimate is finite, its standard deviation grows from the prior by the walk and stays below
// the walk's 30 scans alone, sqrt(0.5^2 + 30 x 0.3^2) = 1.7 deg.
TEST(PoseGraphHeadingBias, AShortStretchInBothBackEnds) {
  Loop loop = make_loop(4, false);
  with_walking_compass(loop, 0.3, 0.1, 4);
  TrajectorySlamConfig front = with_heading_bias(0.3);
  front.calibration.heading_bias_sigma_deg = 0.5;
  for (const int window : {0, 4}) {
    PoseGraphSlamConfig graph;
    graph.online_window_scans = window;
    PoseGraphSlam slam(front.front_end, front.calibration, graph, GaussianPose2{});
    for (std::size_t k = 0; k < 30; ++k) slam.add_scan(loop.scans[k]);
    const CalibrationEstimate beta = slam.calibration().at(0);
    EXPECT_TRUE(std::isfinite(beta.value)) << window;
    EXPECT_GT(beta.sigma, 0.0) << window;
    EXPECT_LT(beta.sigma, std::sqrt(0.25 + 30 * 0.09)) << window;
    slam.finish();
    EXPECT_TRUE(slam.scan_pose_world(29).cov.allFinite()) << window;
  }
}

}  // namespace
}  // namespace msislab
