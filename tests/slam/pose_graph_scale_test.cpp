// The pose graph's constants (trajectory_slam.calibration.range_scale, dvl_scale, clock_offset;
// docs/pose_graph.md, "The scale factors and the clock offset"): one scalar block each for the
// graph, with its prior; every match edge reads the range scale and the clock offset, every
// odometry edge the DVL's scale. The edges' Jacobians against Ceres' numeric ones; on synthetic
// loops whose scans see the world 4 % small, whose DVL reads 3 % long or whose scans are seen
// 0.1 s late, the constant found and the trajectory better than without the block, in the
// whole-graph and the windowed back end (the filters' recovery tests, on the graph).
#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <iostream>
#include <string>
#include <vector>

#include "slam/pose_graph.hpp"
#include "slam/pose_graph_slam.hpp"
#include "tests/slam/residual_jacobian_check.hpp"
#include "tests/slam/synthetic_loop.hpp"

namespace msislab {
namespace {

TEST(PoseGraphScale, EdgeJacobiansMatchCentralDifferences) {
  PoseGraph graph;
  graph.add_node(Pose2(1.0, -2.0, 0.7));
  graph.add_node(Pose2(4.0, 1.5, 2.9));
  EXPECT_THROW(graph.add_scaled_relative(0, 1, {}, Eigen::Matrix3d::Identity(), true,
                                         GraphConstant::kRangeScale),
               std::out_of_range);
  graph.add_constant(GraphConstant::kRangeScale, 0.97, 1.0, 0.05);
  graph.add_constant(GraphConstant::kDvlScale, 1.02, 1.0, 0.02);
  EXPECT_THROW(graph.add_constant(GraphConstant::kRangeScale, 1.0, 1.0, 0.05),
               std::invalid_argument);
  EXPECT_THROW(graph.add_constant(GraphConstant::kDvlScale, 1.0, 1.0, 0.0), std::invalid_argument);
  GaussianPose2 z{Pose2(3.5, 2.0, 2.0), Eigen::Vector3d(0.04, 0.09, 0.001).asDiagonal()};
  z.cov(0, 1) = z.cov(1, 0) = 0.01;
  graph.add_scaled_relative(0, 1, z, Eigen::Matrix3d::Identity(), true, GraphConstant::kRangeScale);
  // A match that leaves a direction out (2 orthonormal rows), not robust.
  Eigen::MatrixXd A = Eigen::MatrixXd::Zero(2, 3);
  A(0, 0) = A(0, 1) = std::sqrt(0.5);
  A(1, 2) = 1.0;
  graph.add_scaled_relative(1, 0, z, A, false, GraphConstant::kRangeScale);
  graph.add_scaled_relative(0, 1, z, Eigen::Matrix3d::Identity(), false, GraphConstant::kDvlScale);
  // Matches through the range scale alone, then through it and the clock offset.
  const Eigen::Vector3d u_0(0.6, 0.1, 0.05), u_1(0.4, -0.2, -0.1);
  graph.add_match(0, 1, z, A, u_0, u_1);
  graph.add_constant(GraphConstant::kClockOffset, 0.3, 0.0, 0.5);
  graph.add_match(1, 0, z, Eigen::Matrix3d::Identity(), u_1, u_0);
  // two priors, three scaled edges, two matches, the clock's prior
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

/// Loops 1..seeds made by loop_of, the graph with the state against the graph without: the
/// smoothed estimate of `name` within two of its standard deviations of `truth` in at least
/// `within` loops and informed below max_sigma, the smoothed trajectory's mean error below the
/// graph's without the state in at least `better`. The bounds are the filters' recovery tests'
/// (tests/slam/calibration_states_test.cpp).
void expect_recovered(int window, unsigned seeds, const std::function<Loop(unsigned)>& loop_of,
                      const TrajectorySlamConfig& with_state, const std::string& name, double truth,
                      double max_sigma, int within, int better) {
  int in = 0, improved = 0;
  PoseGraphSlamConfig graph;
  graph.online_window_scans = window;
  for (unsigned seed = 1; seed <= seeds; ++seed) {
    const Loop loop = loop_of(seed);
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
    EXPECT_EQ(c[0].name, name);
    EXPECT_GT(c[0].sigma, 0.0);
    EXPECT_LT(c[0].sigma, max_sigma);
    in += std::abs(c[0].value - truth) < 2.0 * c[0].sigma;
    improved += with_m < without_m;
    std::cout << "window " << window << ", seed " << seed << ": " << name << " " << c[0].value
              << " +- " << c[0].sigma << ", mean error " << with_m << " m (without " << without_m
              << " m)\n";
    EXPECT_TRUE(ignoring.calibration().empty());
  }
  EXPECT_GE(in, within);
  EXPECT_GE(improved, better);
}

TrajectorySlamConfig with(bool range_scale, bool dvl_scale) {
  TrajectorySlamConfig config;
  config.calibration.range_scale = range_scale;
  config.calibration.dvl_scale = dvl_scale;
  return config;
}

// Ten loops seeing the world 0.96 times its size: within two sd of 0.96 in at least 9 (each with
// probability 0.954 when consistent: 9 or more of 10 with 0.93), better in at least 9.
Loop small_world(unsigned seed) { return scaled(make_loop(seed, false), 0.96); }

TEST(PoseGraphScale, WholeGraphRecoversScansThatSeeTheWorld4PercentSmall) {
  expect_recovered(0, 10, small_world, with(true, false), "range_scale", 0.96, 0.02, 9, 9);
}

TEST(PoseGraphScale, WindowedGraphRecoversScansThatSeeTheWorld4PercentSmall) {
  expect_recovered(8, 10, small_world, with(true, false), "range_scale", 0.96, 0.02, 9, 9);
}

// Five loops whose DVL reads 1.03 times the true velocity: within two sd in at least 4 (5 or 4
// of 5 in 98 % of sets), better in at least 4.
Loop long_dvl(unsigned seed) { return dvl_scaled(make_loop(seed, false), 1.03); }

TEST(PoseGraphScale, WholeGraphRecoversTheDvlScaleOfMotions3PercentLong) {
  expect_recovered(0, 5, long_dvl, with(false, true), "dvl_scale", 1.03, 0.015, 4, 4);
}

TEST(PoseGraphScale, WindowedGraphRecoversTheDvlScaleOfMotions3PercentLong) {
  expect_recovered(8, 5, long_dvl, with(false, true), "dvl_scale", 1.03, 0.015, 4, 4);
}

// Five loops whose scans are seen 0.1 s late (0.4 m along the motion, 9 deg in the turns): the
// filters' bounds, within two sd of 0.1 s in at least 4, sd below 0.05 s, better in at least 4.
Loop late_clock(unsigned seed) { return clock_offset_loop(seed, 0.1); }

TrajectorySlamConfig with_clock() {
  TrajectorySlamConfig config;
  config.calibration.clock_offset = true;
  return config;
}

TEST(PoseGraphScale, WholeGraphRecoversTheSonarClockOffset) {
  expect_recovered(0, 5, late_clock, with_clock(), "clock_offset_s", 0.1, 0.05, 4, 4);
}

TEST(PoseGraphScale, WindowedGraphRecoversTheSonarClockOffset) {
  expect_recovered(8, 5, late_clock, with_clock(), "clock_offset_s", 0.1, 0.05, 4, 4);
}

// The same code on a short stretch of one loop, whole graph and windowed, with the heading bias,
// both scales and the clock offset leading the parameters: what the sanitizer build runs (the
// tests above take minutes under it). Finite estimates, in the filters' order; each scale's and
// the clock's sd below its prior's.
TEST(PoseGraphScale, AShortStretchInBothBackEndsWithEveryParameter) {
  Loop loop = dvl_scaled(scaled(clock_offset_loop(4, 0.1), 0.96), 1.03);
  with_walking_compass(loop, 0.3, 0.1, 4);
  TrajectorySlamConfig front = with_heading_bias(0.3);
  front.calibration.range_scale = front.calibration.dvl_scale = true;
  front.calibration.clock_offset = true;
  for (const int window : {0, 4}) {
    PoseGraphSlamConfig graph;
    graph.online_window_scans = window;
    PoseGraphSlam slam(front, graph, GaussianPose2{});
    for (std::size_t k = 0; k < 30; ++k) slam.add_scan(loop.scans[k]);
    const std::vector<CalibrationEstimate> c = slam.calibration();
    ASSERT_EQ(c.size(), 4u);
    EXPECT_EQ(c[0].name, "range_scale");
    EXPECT_EQ(c[1].name, "dvl_scale");
    EXPECT_EQ(c[2].name, "clock_offset_s");
    EXPECT_EQ(c[3].name, "heading_bias_deg");
    for (const CalibrationEstimate& e : c) EXPECT_TRUE(std::isfinite(e.value)) << window;
    EXPECT_GT(c[0].sigma, 0.0) << window;
    EXPECT_LT(c[0].sigma, 0.05) << window;
    EXPECT_GT(c[1].sigma, 0.0) << window;
    EXPECT_LT(c[1].sigma, 0.02) << window;
    EXPECT_GT(c[2].sigma, 0.0) << window;
    EXPECT_LT(c[2].sigma, 0.5) << window;
    EXPECT_TRUE(slam.scan_pose_world(29).cov.allFinite()) << window;
  }
}

}  // namespace
}  // namespace msislab
