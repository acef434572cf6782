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

/// Ten loops with a compass whose bias starts unknown (drawn from the 1 deg prior) and walks
/// 0.3 deg / sqrt(s) under 0.1 deg of white noise. The statistics are the filters' test's
/// (tests/slam/calibration_states_test.cpp, RecoverTheHeadingBiasOfAWalkingCompass): the bias's
/// mean squared normalised error in the two-sided 99.9 % bounds of chi-square(10) / 10,
/// [0.126, 3.14]; the smoothed last yaw's 1-DOF NEES averaged over the ten loops at most
/// nees_margin above the same graph's on the same loops with a compass that does not walk. Over 30
/// seed offsets that difference was 0.14 +- 0.52 for the whole graph and 0.09 +- 0.31 windowed:
/// margins at 3.3 spreads above the mean, 1.9 and 1.1. Without the state the NEES is far above
/// (10). The graph's own yaw NEES on these loops averages 1.39 (whole) and 1.33 (windowed), not
/// 1, as the filters' does. Was: the bias starting exactly known, the NEES in [0.22, 2.52] (4 and
/// 2 of 20 offsets failed) and the bias within 2 sd in 8 of 10.
void expect_walking_compass_recovered(int window, double nees_margin) {
  struct {
    double nees_with = 0.0, nees_without = 0.0, nees_still = 0.0, z2 = 0.0;
  } out;
  PoseGraphSlamConfig graph;
  graph.online_window_scans = window;
  for (unsigned seed = 1; seed <= 10; ++seed) {
    const WalkingCompassLoops loops = walking_compass_loops(testing::seed(seed));
    const Loop& loop = loops.walking;
    const Loop& still = loops.still;
    const double bias_rad = loops.end_bias_rad;
    const TrajectorySlamConfig with_bias = heading_bias_config();
    PoseGraphSlam estimating(with_bias.front_end, with_bias.calibration, graph, GaussianPose2{});
    PoseGraphSlam ignoring(ScanFrontEndConfig{}, CalibrationStatesConfig{}, graph, GaussianPose2{});
    PoseGraphSlam calibrated(ScanFrontEndConfig{}, CalibrationStatesConfig{}, graph,
                             GaussianPose2{});
    for (const Scan& scan : loop.scans) estimating.add_scan(scan), ignoring.add_scan(scan);
    for (const Scan& scan : still.scans) calibrated.add_scan(scan);
    estimating.finish(), ignoring.finish(), calibrated.finish();
    const std::size_t last = loop.scans.size() - 1;
    const auto yaw_nees = [&](const PoseGraphSlam& slam) {
      const GaussianPose2 pose = slam.scan_pose_world(last);
      const double e = normalize_angle(pose.mean.yaw() - loop.truth[last].yaw());
      return e * e / pose.cov(2, 2);
    };
    out.nees_with += yaw_nees(estimating) / 10.0;
    out.nees_without += yaw_nees(ignoring) / 10.0;
    out.nees_still += yaw_nees(calibrated) / 10.0;
    const std::vector<CalibrationEstimate> c = estimating.calibration();
    EXPECT_EQ(c.size(), 1u);
    EXPECT_EQ(c.at(0).name, "heading_bias_deg");
    out.z2 += std::pow((c[0].value - bias_rad / kDegToRad) / c[0].sigma, 2) / 10.0;
    std::cout << "window " << window << ", seed " << seed << ": bias " << bias_rad / kDegToRad
              << " deg, estimated " << c[0].value << " +- " << c[0].sigma << "\n";
    EXPECT_TRUE(ignoring.calibration().empty());
  }
  std::cout << "window " << window << ": last scan's yaw NEES, 10 loops: " << out.nees_with
            << " with the state, " << out.nees_without << " without, " << out.nees_still
            << " with a calibrated compass; the bias's mean squared normalised error " << out.z2
            << "\n";
  // The filters' statistics (tests/slam/calibration_states_test.cpp,
  // RecoverTheHeadingBiasOfAWalkingCompass): chi-square(10) / 10's two-sided 99.9 % bounds and the
  // yaw NEES's margin over the calibrated compass's.
  EXPECT_GT(out.z2, 0.126);
  EXPECT_LT(out.z2, 3.14);
  EXPECT_LT(out.nees_with, out.nees_still + nees_margin);
  // The change caught: without the state the yaw NEES is hundreds, as in the filters.
  EXPECT_GT(out.nees_without, 10.0);
}

TEST(PoseGraphHeadingBias, WholeGraphRecoversAWalkingCompassesBias) {
  expect_walking_compass_recovered(0, 1.9);
}

TEST(PoseGraphHeadingBias, WindowedGraphRecoversAWalkingCompassesBias) {
  expect_walking_compass_recovered(8, 1.1);
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
