// The channel consistency test (issue 12): `msislab montecarlo` on scenarios/straight_channel.yaml
// (a loop in a basin, then 145 m down a straight channel with smooth walls, where the scans do
// not fix the motion along the axis), 4 seeded runs (seeds 1-4) of robocentric SLAM and dead
// reckoning. It asserts that the SLAM stays consistent in the channel and beats dead reckoning
// there on average. Measured figures beside each tolerance (these 4 runs); without match
// validation (`validation.restart_offset_m: 0`) the same runs give ANEES 15.8 and about 45 % of
// the scans in bounds, which this test fails (docs/trajectory_slam.md, "Match validation").
#include <gtest/gtest.h>

#include <cmath>
#include <iostream>
#include <sstream>
#include <stdexcept>
#include <string>

#include "app/montecarlo_command.hpp"
#include "test_support.hpp"

namespace msislab::app {
namespace {

constexpr int kRuns = 4;

const MethodSummary& find(const MonteCarloOutcome& outcome, const std::string& method) {
  for (const MethodSummary& s : outcome.summary) {
    if (s.method == method) return s;
  }
  throw std::runtime_error("no summary for " + method);
}

double segment(const MethodSummary& s, const std::string& name) {
  for (const auto& [segment_name, value] : s.segments) {
    if (segment_name == name) return value.value_or(NAN);
  }
  return NAN;
}

// One test, so that ctest runs the Monte Carlo once (about 11 s on 2 cores).
TEST(StraightChannel, SlamStaysConsistentAlongTheChannel) {
  const testing::TempDir tmp;
  MonteCarloOptions options;
  options.scenario_path = std::string(MSISLAB_SOURCE_DIR) + "/scenarios/straight_channel.yaml";
  options.runs = kRuns;
  options.out_dir = tmp.file("mc");
  options.methods = {"robocentric", "deadreckoning"};
  options.jobs = 2;
  options.executable = MSISLAB_EXE;
  std::ostringstream log;
  const MonteCarloOutcome outcome = montecarlo(options, {log, false});
  ASSERT_EQ(outcome.failed, 0u) << log.str();

  const MethodSummary& slam = find(outcome, "robocentric");
  const MethodSummary& dr = find(outcome, "deadreckoning");
  ASSERT_EQ(slam.runs, kRuns);
  ASSERT_EQ(dr.runs, kRuns);
  const double slam_channel_m = segment(slam, "channel"), dr_channel_m = segment(dr, "channel");
  std::cout << "robocentric: mean error " << slam.mean_error_m.value_or(NAN) << " m, channel "
            << slam_channel_m << " m (dead reckoning " << dr_channel_m << " m), ANEES "
            << slam.anees.value_or(NAN) << ", NEES in bounds "
            << slam.nees_in_bounds_fraction.value_or(NAN) << "\n";

  EXPECT_LT(slam.mean_error_m.value_or(INFINITY), 2.2);  // 1.53 m
  // 2.40 against 6.33 m; seed 1 alone still ends the channel behind (2.89 against 2.39 m).
  EXPECT_LT(slam_channel_m, 0.6 * dr_channel_m);
  std::ostringstream outside;
  for (std::size_t k = 0; k < slam.nees.size(); ++k) {
    if (!slam.nees[k].inside()) {
      outside << " scan " << k << ": " << slam.nees[k].mean << " not in [" << slam.nees[k].lower
              << ", " << slam.nees[k].upper << "];";
    }
  }
  // 0.988 (84 of 85 scans; scan 12 at 8.5, in the basin's first corner).
  EXPECT_GE(slam.nees_in_bounds_fraction.value_or(0.0), 0.85) << outside.str();
  EXPECT_GT(slam.anees.value_or(0.0), 1.5);       // 2.48
  EXPECT_LT(slam.anees.value_or(INFINITY), 4.5);  // 2.48
}

}  // namespace
}  // namespace msislab::app
