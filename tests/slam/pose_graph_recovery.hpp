// The pose graph's calibration recovery on synthetic loops (the filters' recovery tests,
// tests/slam/calibration_states_test.cpp, on the graph): shared by the constants' tests.
#pragma once

#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <iostream>
#include <string>
#include <vector>

#include "slam/pose_graph_slam.hpp"
#include "stats/chi_square.hpp"
#include "test_support.hpp"
#include "tests/slam/synthetic_loop.hpp"

namespace msislab {

/// A calibration value a recovery test expects: its name (as calibration() gives it), its true
/// value and the largest standard deviation its estimate may keep (the loop informs it).
struct ExpectedEstimate {
  std::string name;
  double truth = 0.0;
  double max_sigma = 0.0;
};

/// Loops 1..seeds made by loop_of, the graph with the state against the graph without (window:
/// online_window_scans): the smoothed estimates, named and ordered as `expected`, each informed
/// below its max_sigma; their squared normalised errors ((estimate - truth) / sigma)^2, each
/// chi-square with 1 degree of freedom when the estimate is consistent, averaged over every loop
/// and value inside average_chi2_bounds(n, 1, 0.001) (the filters' statistic,
/// tests/slam/calibration_states_test.cpp, expect_consistent: a false alarm of 0.001; over 10
/// estimates a standard deviation understated 2.5 times is caught 9 times in 10); and the smoothed
/// trajectory's mean error below the graph's without the state in at least `better` loops.
inline void expect_recovered(int window, unsigned seeds,
                             const std::function<Loop(unsigned)>& loop_of,
                             const TrajectorySlamConfig& with_state,
                             const std::vector<ExpectedEstimate>& expected, int better) {
  int estimates = 0, improved = 0;
  double mean_z2 = 0.0;
  PoseGraphSlamConfig graph;
  graph.online_window_scans = window;
  for (unsigned seed = 1; seed <= seeds; ++seed) {
    const Loop loop = loop_of(testing::seed(seed));
    PoseGraphSlam estimating(with_state.front_end, with_state.calibration, graph, GaussianPose2{});
    PoseGraphSlam ignoring(ScanFrontEndConfig{}, CalibrationStatesConfig{}, graph, GaussianPose2{});
    for (const Scan& scan : loop.scans) estimating.add_scan(scan), ignoring.add_scan(scan);
    estimating.finish(), ignoring.finish();
    const auto mean_error_m = [&](const PoseGraphSlam& slam) {
      double sum = 0.0;
      for (std::size_t i = 0; i < slam.scans(); ++i) {
        sum += (slam.scan_pose_world(i).mean.translation() - loop.truth[i].translation()).norm();
      }
      return sum / static_cast<double>(slam.scans());
    };
    const double with_m = mean_error_m(estimating), without_m = mean_error_m(ignoring);
    // Read after the smoothed trajectory, as a run reads it: the smoothed graph's estimates.
    const std::vector<CalibrationEstimate> c = estimating.calibration();
    ASSERT_EQ(c.size(), expected.size());
    std::cout << "window " << window << ", seed " << seed << ":";
    for (std::size_t i = 0; i < c.size(); ++i) {
      EXPECT_EQ(c[i].name, expected[i].name);
      EXPECT_GT(c[i].sigma, 0.0);
      EXPECT_LT(c[i].sigma, expected[i].max_sigma) << "seed " << seed << ": " << c[i].name;
      const double z = (c[i].value - expected[i].truth) / c[i].sigma;
      mean_z2 += z * z;
      ++estimates;
      std::cout << " " << c[i].name << " " << c[i].value << " +- " << c[i].sigma << " (z " << z
                << ")";
    }
    improved += with_m < without_m;
    std::cout << ", mean error " << with_m << " m (without " << without_m << " m)\n";
    EXPECT_TRUE(ignoring.calibration().empty());
  }
  ASSERT_GT(estimates, 0);
  mean_z2 /= estimates;
  const auto [lower, upper] = average_chi2_bounds(estimates, 1, 0.001);
  std::cout << "window " << window << ": mean squared normalised error " << mean_z2 << " over "
            << estimates << " estimates, bounds [" << lower << ", " << upper << "]\n";
  EXPECT_GT(mean_z2, lower);
  EXPECT_LT(mean_z2, upper);
  EXPECT_GE(improved, better);
}

}  // namespace msislab
