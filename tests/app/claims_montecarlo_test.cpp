// The Monte Carlo claims of docs/claims.yaml (tests/app/claims_test.cpp has the others): the
// replica's 50 seeded runs through its detections with config/stpere_replica.yaml, the flagship
// path of the README. Its first 6 runs (the same seeds, so the same bytes as runs 0-5 of the 50)
// are made here, and each claim is checked within the Monte Carlo error of a 6-run figure as an
// estimate of the 50-run one (check_montecarlo_claim). Within the same 6 runs SLAM must beat its
// dead reckoning, as the README says it does.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <iostream>
#include <map>
#include <sstream>
#include <string>

#include "app/montecarlo.hpp"
#include "method_summary_lookup.hpp"
#include "results/results.hpp"
#include "settings/expectations_yaml.hpp"
#include "test_support.hpp"

namespace msislab {
namespace {

namespace fs = std::filesystem;

const std::string kSource = MSISLAB_SOURCE_DIR;
constexpr int kRuns = 6;
// Two-sided 99.9 % normal quantile: a claim that holds is missed once in a thousand subsets.
constexpr double kZ = 3.29;

/// Every run's metrics.json figure `metric` for one method, in run order.
std::vector<double> per_run(const fs::path& mc, const std::string& method,
                            const std::string& metric) {
  std::vector<double> values;
  for (int r = 0; r < kRuns; ++r) {
    char name[16];
    std::snprintf(name, sizeof name, "run_%04d", r);
    const RunMetrics m =
        results::read_metrics_json((mc / "runs" / method / name / "metrics.json").string()).metrics;
    if (metric == "mean_error_m") values.push_back(m.errors.mean_m);
    if (metric == "final_error_m") values.push_back(m.errors.final_m);
    if (metric == "anees") values.push_back(m.anees.value_or(NAN));
    for (const auto& [segment, value] : m.segments) {
      if (metric == "segments." + segment) values.push_back(value.value_or(NAN));
    }
  }
  return values;
}

/// A claim on the N-run Monte Carlo (N: its claimed run count) against the first n = kRuns runs.
/// A mean over the runs (mean error, ANEES, a segment's error): the n-run mean estimates the
/// N-run mean of the same seeds with variance (s^2 / n)(1 - n / N), s the n runs' sample standard
/// deviation (sampling n of N without replacement); the claim holds within kZ of its standard
/// error plus its own rounding (tolerance). A count of runs (runs_not_lower, k of N runs): the
/// count among the n is hypergeometric with mean n k / N and variance n p (1 - p) (N - n) / (N -
/// 1), p = k / N; it holds within kZ standard deviations plus one half (the count is whole).
void check_montecarlo_claim(const Expectation& claim, const fs::path& mc, int claimed_runs) {
  SCOPED_TRACE(claim.location + ": " + claim.name);
  ASSERT_TRUE(claim.equals.has_value());
  const double n = kRuns;
  const double big_n = claimed_runs;
  if (claim.metric == "paired_difference.runs_not_lower") {
    const std::vector<double> own = per_run(mc, claim.method, "mean_error_m");
    const std::vector<double> reference = per_run(mc, "robocentric", "mean_error_m");
    double k = 0;
    for (int r = 0; r < kRuns; ++r) k += own[r] >= reference[r] ? 1 : 0;
    const double p = *claim.equals / big_n;
    const double sd = std::sqrt(n * p * (1 - p) * (big_n - n) / (big_n - 1));
    std::cout << claim.name << ": " << k << " of " << kRuns << " runs, claimed " << *claim.equals
              << " of " << claimed_runs << " (expected " << n * p << " +- " << sd << ")\n";
    EXPECT_LE(std::abs(k - n * p), kZ * sd + 0.5);
    return;
  }
  const std::vector<double> values = per_run(mc, claim.method, claim.metric);
  ASSERT_EQ(values.size(), static_cast<std::size_t>(kRuns))
      << "no Monte Carlo error rule for " << claim.metric;
  double mean = 0.0;
  for (const double v : values) mean += v / n;
  double ss = 0.0;
  for (const double v : values) ss += (v - mean) * (v - mean);
  const double se = std::sqrt(ss / (n - 1) / n * (1 - n / big_n));
  std::cout << claim.name << ": " << mean << " over " << kRuns << " runs, claimed " << *claim.equals
            << " over " << claimed_runs << " (standard error " << se << ")\n";
  EXPECT_LE(std::abs(mean - *claim.equals), kZ * se + claim.tolerance);
}

TEST(ClaimsMonteCarlo, TheReplicasFirstRunsHoldItsClaimsWithinTheirMonteCarloError) {
  std::vector<Expectation> claims;
  std::vector<std::string> methods = {"robocentric", "deadreckoning"};  // robocentric the reference
  int claimed_runs = 0;
  for (const Expectation& e : settings::read_expectations_yaml(kSource + "/docs/claims.yaml")) {
    if (e.result != "replica_mc") continue;
    if (std::find(methods.begin(), methods.end(), e.method) == methods.end()) {
      methods.push_back(e.method);
    }
    if (e.metric == "runs") {
      claimed_runs = static_cast<int>(e.equals.value_or(0));  // a setting, not a statistic
    } else {
      claims.push_back(e);
    }
  }
  ASSERT_GT(claimed_runs, kRuns) << "docs/claims.yaml: the replica's run count is not claimed";
  ASSERT_FALSE(claims.empty());

  const testing::TempDir tmp;
  app::MonteCarloOptions options;
  options.scenario_path = kSource + "/scenarios/stpere_replica.yaml";
  options.config_path = kSource + "/config/stpere_replica.yaml";
  options.runs = kRuns;
  options.out_dir = tmp.file("mc");
  options.methods = methods;
  options.jobs = 2;
  std::ostringstream log;
  const app::MonteCarloOutcome outcome = app::montecarlo(options, {log, false});
  ASSERT_EQ(outcome.failed, 0u) << log.str();
  for (const Expectation& claim : claims)
    check_montecarlo_claim(claim, options.out_dir, claimed_runs);

  // The flagship claim itself: over these runs, SLAM below its dead reckoning beyond the Monte
  // Carlo noise (the paired difference's 95 % interval above 0 for dead reckoning minus SLAM).
  const MethodSummary& dr = app::testing_lookup::find(outcome, "deadreckoning");
  const MethodSummary& rc = app::testing_lookup::find(outcome, "robocentric");
  std::cout << "robocentric " << rc.mean_error_m.value_or(NAN) << " m, dead reckoning "
            << dr.mean_error_m.value_or(NAN) << " m over " << kRuns << " runs\n";
  ASSERT_TRUE(dr.paired.has_value());
  EXPECT_EQ(dr.paired->reference, "robocentric");
  EXPECT_GT(dr.paired->ci95_lower_m, 0.0)
      << "dead reckoning minus SLAM: " << dr.paired->mean_m << " m, 95 % interval ["
      << dr.paired->ci95_lower_m << ", " << dr.paired->ci95_upper_m << "]";
}

}  // namespace
}  // namespace msislab
