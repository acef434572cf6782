// The failure scenarios' consistency tests: `msislab montecarlo`, 4 seeded runs (seeds
// 1-4) of robocentric SLAM and dead reckoning, on the scenes where scan matching is weakest.
// Each asserts that the SLAM stays consistent there and beats dead reckoning on average. Measured
// figures beside each tolerance (these 4 runs).
// - scenarios/straight_channel.yaml: a loop in a basin, then 145 m down a straight channel with
//   smooth walls, where the scans do not fix the motion along the axis. Without match validation
//   (`validation.restart_offset_m: 0`) the same runs give ANEES 15.8 and about 45 % of the scans
//   in bounds, which this test fails (docs/trajectory_slam.md, "Match validation").
// - scenarios/open_area.yaml: a loop in a corner of two quays, then a loop in open water with only
//   a few mooring dolphins in range (5-20 points a scan; about half of those scans hold fewer
//   than spIC's 8 and are not matched).
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

constexpr int kRuns = 4;

using testing_lookup::find;

using testing_lookup::segment;

/// The scans outside their NEES bounds, for a failure message.
std::string scans_outside(const MethodSummary& s) {
  std::ostringstream outside;
  for (std::size_t k = 0; k < s.nees.size(); ++k) {
    if (!s.nees[k].inside()) {
      outside << " scan " << k << ": " << s.nees[k].mean << " not in [" << s.nees[k].lower << ", "
              << s.nees[k].upper << "];";
    }
  }
  return outside.str();
}

/// kRuns runs of robocentric SLAM and dead reckoning on a shipped scenario; prints the summary of
/// the SLAM and both methods' error in `segment_name`.
MonteCarloOutcome run_scenario(const testing::TempDir& tmp, const std::string& scenario,
                               const std::string& segment_name) {
  MonteCarloOptions options;
  options.scenario_path = std::string(MSISLAB_SOURCE_DIR) + "/scenarios/" + scenario;
  options.runs = kRuns;
  options.out_dir = tmp.file("mc");
  options.methods = {"robocentric", "deadreckoning"};
  options.jobs = 2;
  std::ostringstream log;
  MonteCarloOutcome outcome = montecarlo(options, {log, false});
  EXPECT_EQ(outcome.failed, 0u) << log.str();
  const MethodSummary& slam = find(outcome, "robocentric");
  const MethodSummary& dr = find(outcome, "deadreckoning");
  EXPECT_EQ(slam.runs, kRuns);
  EXPECT_EQ(dr.runs, kRuns);
  std::cout << scenario << ", robocentric: mean error " << slam.mean_error_m.value_or(NAN) << " m, "
            << segment_name << " " << segment(slam, segment_name) << " m (dead reckoning "
            << segment(dr, segment_name) << " m), ANEES " << slam.anees.value_or(NAN)
            << ", NEES in bounds " << slam.nees_in_bounds_fraction.value_or(NAN) << "\n";
  return outcome;
}

// One test per scenario, so that ctest runs each Monte Carlo once (about 11 s on 2 cores).
TEST(StraightChannel, SlamStaysConsistentAlongTheChannel) {
  const testing::TempDir tmp;
  const MonteCarloOutcome outcome = run_scenario(tmp, "straight_channel.yaml", "channel");
  ASSERT_EQ(outcome.failed, 0u);
  const MethodSummary& slam = find(outcome, "robocentric");
  const MethodSummary& dr = find(outcome, "deadreckoning");
  const double slam_channel_m = segment(slam, "channel"), dr_channel_m = segment(dr, "channel");

  EXPECT_LT(slam.mean_error_m.value_or(INFINITY), 2.2);  // 1.53 m
  // 2.40 against 6.33 m; seed 1 alone still ends the channel behind (2.89 against 2.39 m).
  EXPECT_LT(slam_channel_m, 0.6 * dr_channel_m);
  // 0.988 (84 of 85 scans; scan 12 at 8.5, in the basin's first corner).
  EXPECT_GE(slam.nees_in_bounds_fraction.value_or(0.0), 0.85) << scans_outside(slam);
  EXPECT_GT(slam.anees.value_or(0.0), 1.5);       // 2.48
  EXPECT_LT(slam.anees.value_or(INFINITY), 4.5);  // 2.48
}

TEST(OpenArea, SlamStaysConsistentWithSparseReturns) {
  const testing::TempDir tmp;
  const MonteCarloOutcome outcome = run_scenario(tmp, "open_area.yaml", "open");
  ASSERT_EQ(outcome.failed, 0u);
  const MethodSummary& slam = find(outcome, "robocentric");
  const MethodSummary& dr = find(outcome, "deadreckoning");
  EXPECT_LT(slam.mean_error_m.value_or(INFINITY), 2.0);         // 1.47 m
  EXPECT_LT(segment(slam, "open"), 0.5 * segment(dr, "open"));  // 2.65 against 7.61 m
  EXPECT_GE(slam.nees_in_bounds_fraction.value_or(0.0), 0.85) << scans_outside(slam);  // 0.958
  EXPECT_GT(slam.anees.value_or(0.0), 1.5);
  EXPECT_LT(slam.anees.value_or(INFINITY), 4.5);
}

}  // namespace
}  // namespace msislab::app
