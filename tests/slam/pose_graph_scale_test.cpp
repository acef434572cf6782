// The pose graph's constants (trajectory_slam.calibration.range_scale, dvl_scale, clock_offset;
// docs/pose_graph.md, "The scale factors, the clock offset and the compass deviation"): one scalar
// block each for the graph, with its prior; every match edge reads the range scale and the clock
// offset, every odometry edge the DVL's scale. The edges' Jacobians against Ceres' numeric ones; on
// synthetic loops whose scans see the world 4 % small, whose DVL reads 3 % long or whose scans are
// seen 0.1 s late, the constant found and the trajectory better than without the block, in the
// whole-graph and the windowed back end (the filters' recovery tests, on the graph).
#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <iostream>
#include <string>
#include <vector>

#include "slam/pose_graph.hpp"
#include "slam/pose_graph_slam.hpp"
#include "tests/slam/pose_graph_recovery.hpp"
#include "tests/slam/residual_jacobian_check.hpp"
#include "tests/slam/synthetic_loop.hpp"

namespace msislab {
namespace {

TEST(PoseGraphScale, EdgeJacobiansMatchCentralDifferences) {
  PoseGraph graph;
  graph.add_node(Pose2(1.0, -2.0, 0.7));
  graph.add_node(Pose2(4.0, 1.5, 2.9));
  graph.add_constant(GraphConstant::kRangeScale, 0.97, 1.0, 0.05);
  graph.add_constant(GraphConstant::kDvlScale, 1.02, 1.0, 0.02);
  EXPECT_THROW(graph.add_constant(GraphConstant::kRangeScale, 1.0, 1.0, 0.05),
               std::invalid_argument);
  EXPECT_THROW(graph.add_constant(GraphConstant::kDvlScale, 1.0, 1.0, 0.0), std::invalid_argument);
  GaussianPose2 z{Pose2(3.5, 2.0, 2.0), Eigen::Vector3d(0.04, 0.09, 0.001).asDiagonal()};
  z.cov(0, 1) = z.cov(1, 0) = 0.01;
  // Matches through the range scale alone, one leaving a direction out (2 orthonormal rows); an
  // odometry edge through the DVL's scale; then matches through the range scale and the clock.
  const Eigen::Vector3d u_0(0.6, 0.1, 0.05), u_1(0.4, -0.2, -0.1);
  Eigen::MatrixXd A = Eigen::MatrixXd::Zero(2, 3);
  A(0, 0) = A(0, 1) = std::sqrt(0.5);
  A(1, 2) = 1.0;
  graph.add_match(0, 1, z, Eigen::Matrix3d::Identity(), u_0, u_1);
  graph.add_match(1, 0, z, A, u_1, u_0);
  graph.add_odometry(0, 1, z, true);
  graph.add_constant(GraphConstant::kClockOffset, 0.3, 0.0, 0.5);
  graph.add_match(0, 1, z, A, u_0, u_1);
  graph.add_match(1, 0, z, Eigen::Matrix3d::Identity(), u_1, u_0);
  // two priors, two scaled matches, the scaled odometry, the clock's prior, two clocked matches
  expect_residual_jacobians_match(graph.problem_for_checks(), 8);
}

TEST(PoseGraphScale, AMatchThroughTheClockAloneHasItsJacobians) {
  PoseGraph graph;
  graph.add_node(Pose2(1.0, -2.0, 0.7));
  graph.add_node(Pose2(4.0, 1.5, 2.9));
  graph.add_constant(GraphConstant::kClockOffset, -0.2, 0.0, 0.5);
  const GaussianPose2 z{Pose2(3.5, 2.0, 2.0), Eigen::Vector3d(0.04, 0.09, 0.001).asDiagonal()};
  graph.add_match(0, 1, z, Eigen::Matrix3d::Identity(), Eigen::Vector3d(0.6, 0.1, 0.05),
                  Eigen::Vector3d(0.4, -0.2, -0.1));
  expect_residual_jacobians_match(graph.problem_for_checks(), 2);
}

TrajectorySlamConfig with(bool range_scale, bool dvl_scale) {
  TrajectorySlamConfig config;
  config.calibration.range_scale = range_scale;
  config.calibration.dvl_scale = dvl_scale;
  return config;
}

// Ten loops seeing the world 0.96 times its size: the estimates consistent (expect_recovered's
// mean squared normalised error), better in at least 9. (Was: within two sd in at least 9 of 10,
// a false alarm of 0.07: 2 of 20 seed offsets failed in each back end.)
Loop small_world(unsigned seed) { return scaled(make_loop(seed, false), 0.96); }

TEST(PoseGraphScale, WholeGraphRecoversScansThatSeeTheWorld4PercentSmall) {
  expect_recovered(0, 10, small_world, with(true, false), {{"range_scale", 0.96, 0.02}}, 9);
}

TEST(PoseGraphScale, WindowedGraphRecoversScansThatSeeTheWorld4PercentSmall) {
  expect_recovered(8, 10, small_world, with(true, false), {{"range_scale", 0.96, 0.02}}, 9);
}

// Ten loops whose DVL reads 1.03 times the true velocity: the estimates consistent, better in at
// least 8 (the filters' rule). (Was: five loops, within two sd in at least 4.)
Loop long_dvl(unsigned seed) { return dvl_scaled(make_loop(seed, false), 1.03); }

TEST(PoseGraphScale, WholeGraphRecoversTheDvlScaleOfMotions3PercentLong) {
  expect_recovered(0, 10, long_dvl, with(false, true), {{"dvl_scale", 1.03, 0.015}}, 8);
}

TEST(PoseGraphScale, WindowedGraphRecoversTheDvlScaleOfMotions3PercentLong) {
  expect_recovered(8, 10, long_dvl, with(false, true), {{"dvl_scale", 1.03, 0.015}}, 8);
}

// The filters' clock-offset loops (tests/slam/calibration_states_test.cpp,
// RecoverTheSonarClockOffset): St. Pere's timing, 13.8 s between scans, the sonar's clock 0.66 s
// behind, the scans carrying the dead reckoning's velocity as a run's do. Ten loops: the filters'
// statistic and rules, the estimates consistent, sd below 0.1 s, better in at least 8. (Was: 1 s
// between scans, 0.1 s late, the truth's velocity.) Over 20 seed offsets as the filters: normalised
// errors of mean -0.25 and sd 1.12 (whole graph) and -0.24 and 1.09 (window), the whole graph's
// mean square past the 99.9 % bound once (offset 3000: 3.20, as the filters), the state improving
// 399 of the 400 loops.
Loop late_clock(unsigned seed) {
  return clock_offset_loop(seed, 0.66, ScanVelocity::kDeadReckoning, 13.8);
}

TrajectorySlamConfig with_clock() {
  TrajectorySlamConfig config;
  config.calibration.clock_offset = true;
  return config;
}

TEST(PoseGraphScale, WholeGraphRecoversTheSonarClockOffset) {
  expect_recovered(0, 10, late_clock, with_clock(), {{"clock_offset_s", 0.66, 0.1}}, 8);
}

TEST(PoseGraphScale, WindowedGraphRecoversTheSonarClockOffset) {
  expect_recovered(8, 10, late_clock, with_clock(), {{"clock_offset_s", 0.66, 0.1}}, 8);
}

// The same code on a short stretch of one loop, whole graph and windowed, with the heading bias,
// both scales, the clock offset and the compass deviation leading the parameters: what the
// sanitizer build runs (the tests above take minutes under it). Finite estimates, in the filters'
// order; each constant's sd below its prior's.
TEST(PoseGraphScale, AShortStretchInBothBackEndsWithEveryParameter) {
  Loop loop = dvl_scaled(scaled(clock_offset_loop(4, 0.1), 0.96), 1.03);
  with_walking_compass(loop, 0.3, 0.1, 4);
  TrajectorySlamConfig front = with_heading_bias(0.3);
  front.calibration.range_scale = front.calibration.dvl_scale = true;
  front.calibration.clock_offset = front.calibration.compass_deviation = true;
  for (const int window : {0, 4}) {
    PoseGraphSlamConfig graph;
    graph.online_window_scans = window;
    PoseGraphSlam slam(front.front_end, front.calibration, graph, GaussianPose2{});
    for (std::size_t k = 0; k < 30; ++k) slam.add_scan(loop.scans[k]);
    const std::vector<CalibrationEstimate> c = slam.calibration();
    const std::vector<std::string> names = {"range_scale",
                                            "dvl_scale",
                                            "clock_offset_s",
                                            "heading_bias_deg",
                                            "compass_deviation_cos_deg",
                                            "compass_deviation_sin_deg"};
    const std::vector<double> prior_sd = {0.05, 0.02, 0.5, 0.3, 3.0, 3.0};
    ASSERT_EQ(c.size(), names.size());
    for (std::size_t i = 0; i < c.size(); ++i) {
      EXPECT_EQ(c[i].name, names[i]);
      EXPECT_TRUE(std::isfinite(c[i].value)) << window << " " << names[i];
      EXPECT_GT(c[i].sigma, 0.0) << window << " " << names[i];
      if (names[i] != "heading_bias_deg") {  // the bias walks: its sd grows past its prior's
        EXPECT_LT(c[i].sigma, prior_sd[i]) << window << " " << names[i];
      }
    }
    slam.finish();
    EXPECT_TRUE(slam.scan_pose_world(29).cov.allFinite()) << window;
  }
}

}  // namespace
}  // namespace msislab
