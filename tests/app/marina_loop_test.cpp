// The CI end-to-end SLAM test: `msislab montecarlo` on scenarios/marina_loop.yaml (a
// 546 s, 39-scan loop in the marina basin, no real data needed), 5 seeded runs (seeds 1-5) of
// robocentric, world-centric, the pose graph and dead reckoning. It asserts the SLAM error, its
// gain over dead reckoning, and that the robocentric scan-pose NEES averaged over the runs stays
// inside its 95% chi-square bounds for most scans. Measured figures beside each tolerance: this
// directory's 5 runs, then the range over the 8 blocks of 5 runs of seeds 1-40
// (docs/trajectory_slam.md), both measured with one-way spIC association; with the reciprocal
// default these 5 runs give 0.720 m, ANEES 3.32 and 94.9% of the scans in bounds.
#include <gtest/gtest.h>

#include <cmath>
#include <iostream>
#include <sstream>
#include <stdexcept>
#include <string>

#include "app/montecarlo.hpp"
#include "method_summary_lookup.hpp"
#include "test_support.hpp"

namespace msislab::app {
namespace {

constexpr int kRuns = 5;

using testing_lookup::find;

void expect_errors(const MonteCarloOutcome& outcome) {
  const double robocentric_m = find(outcome, "robocentric").mean_error_m.value_or(NAN);
  const double worldcentric_m = find(outcome, "worldcentric").mean_error_m.value_or(NAN);
  const double dead_reckoning_m = find(outcome, "deadreckoning").mean_error_m.value_or(NAN);
  EXPECT_LT(robocentric_m, 1.0);     // 0.698 m; blocks 0.57-0.80 m
  EXPECT_GT(dead_reckoning_m, 2.0);  // 3.07 m; blocks 2.72-3.96 m: the loop has something to fix
  EXPECT_LT(robocentric_m, 0.4 * dead_reckoning_m);  // 0.23 of it; blocks 0.20-0.28
  // The two parameterisations of one IEKF (docs/trajectory_slam.md): 1e-4 m apart here.
  EXPECT_NEAR(worldcentric_m, robocentric_m, 0.01);
}

void expect_consistent(const MethodSummary& robocentric) {
  ASSERT_EQ(robocentric.nees.size(), 39u);
  std::ostringstream outside;
  for (std::size_t k = 0; k < robocentric.nees.size(); ++k) {
    const AveragedNees& step = robocentric.nees[k];
    EXPECT_EQ(step.runs, kRuns);
    if (!step.inside()) {
      outside << " scan " << k << ": " << step.mean << " not in [" << step.lower << ", "
              << step.upper << "];";
    }
  }
  // A consistent filter: 0.95 expected. 0.949 (37 of 39; scans 5 and 34 at 5.56 and 5.58, just
  // above 5.50); blocks 0.87-0.97, where scan 17 is the one most often out (centred on the second
  // corner's yaw-rate jump, where the dead-reckoning heading lags by about 1 deg).
  EXPECT_GE(robocentric.nees_in_bounds_fraction.value_or(0.0), 0.85) << outside.str();
  // Consistent: 3. 3.04; blocks 2.13-3.93 (scans of one run share their errors, so the average
  // over 39 scans varies more than 585 independent NEES would); seeds 1-40 together: 2.91.
  EXPECT_GT(robocentric.anees.value_or(0.0), 1.8);
  EXPECT_LT(robocentric.anees.value_or(INFINITY), 4.5);
}

// One test, so that ctest runs the Monte Carlo once (7-10 s alone on 2 cores, 14 s in the suite).
TEST(MarinaLoop, SlamBeatsDeadReckoningAndRobocentricNeesStaysInBounds) {
  const testing::TempDir tmp;
  MonteCarloOptions options;
  options.scenario_path = std::string(MSISLAB_SOURCE_DIR) + "/scenarios/marina_loop.yaml";
  options.runs = kRuns;
  options.out_dir = tmp.file("mc");
  options.methods = {"robocentric", "worldcentric", "posegraph", "deadreckoning"};
  options.jobs = 2;
  std::ostringstream log;
  const MonteCarloOutcome outcome = montecarlo(options, {log, false});

  ASSERT_EQ(outcome.failed, 0u) << log.str();
  for (const MethodSummary& s : outcome.summary) {
    ASSERT_EQ(s.runs, kRuns) << s.method;
    std::cout << s.method << ": mean error " << s.mean_error_m.value_or(NAN) << " m, ANEES "
              << s.anees.value_or(NAN) << ", NEES in bounds "
              << s.nees_in_bounds_fraction.value_or(NAN) << "\n";
  }
  expect_errors(outcome);
  expect_consistent(find(outcome, "robocentric"));

  // The pose graph on the same scans: online 0.602 m, smoothed 0.634 m, ANEES 1.92
  // (its online covariances a little wide), 79.5 % of the scans in bounds.
  const MethodSummary& graph = find(outcome, "posegraph");
  const double graph_m = graph.mean_error_m.value_or(NAN);
  EXPECT_LT(graph_m, 1.0);
  EXPECT_LT(graph_m, 0.4 * find(outcome, "deadreckoning").mean_error_m.value_or(NAN));
  double smoothed_m = NAN;
  for (const auto& [name, value] : graph.diagnostics) {
    if (name == "smoothed_mean_error_m") smoothed_m = value;
  }
  EXPECT_LT(smoothed_m, 1.0);
  EXPECT_GT(graph.anees.value_or(0.0), 1.0);
  EXPECT_LT(graph.anees.value_or(INFINITY), 4.5);
}

}  // namespace
}  // namespace msislab::app
