// Monte Carlo statistics: per-scan NEES averaged over runs of different lengths with the bounds for
// that number of runs, the in-bounds fraction (about 95% for consistent chi-square samples), and
// the summary of finished, failed and missing runs.
#include "eval/monte_carlo.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <random>

#include "stats/chi_square.hpp"
#include "stats/sample_statistics.hpp"
#include "test_support.hpp"

namespace msislab {
namespace {

TEST(MonteCarlo, AveragesEachScanOverTheRunsThatReachedIt) {
  const std::vector<AveragedNees> steps = average_nees_over_runs({{1.0, 2.0, 9.0}, {3.0, 4.0}});
  ASSERT_EQ(steps.size(), 3u);
  EXPECT_EQ(steps[0].runs, 2);
  EXPECT_DOUBLE_EQ(steps[0].mean, 2.0);
  EXPECT_DOUBLE_EQ(steps[1].mean, 3.0);
  EXPECT_EQ(steps[2].runs, 1);
  EXPECT_DOUBLE_EQ(steps[2].mean, 9.0);
  const auto [lower2, upper2] = average_chi2_bounds(2, 3, 0.05);
  EXPECT_EQ(steps[0].lower, lower2);
  EXPECT_EQ(steps[0].upper, upper2);
  EXPECT_EQ(steps[2].lower, average_chi2_bounds(1, 3, 0.05).first);
  // field-notes: N = 50 gives [2.36, 3.72] (the Wilson-Hilferty bounds are close for N >= 25;
  // at N = 1 they give [0.18, 9.4] for the exact [0.216, 9.35]).
  const AveragedNees fifty = average_nees_over_runs(std::vector<std::vector<double>>(50, {3.0}))[0];
  EXPECT_EQ(fifty.runs, 50);
  EXPECT_NEAR(fifty.lower, 2.36, 0.01);
  EXPECT_NEAR(fifty.upper, 3.72, 0.01);
  EXPECT_TRUE(steps[0].inside());
  EXPECT_TRUE(steps[2].inside());
  EXPECT_DOUBLE_EQ(*fraction_inside(steps), 1.0);
  EXPECT_FALSE(fraction_inside({}));
  EXPECT_TRUE(average_nees_over_runs({}).empty());
}

TEST(MonteCarlo, ConsistentSamplesAreInsideAboutNinetyFivePercentOfTheTime) {
  // 50 runs x 400 scans of exact 3-DOF NEES: e ~ N(0, I), NEES = |e|^2.
  std::mt19937_64 rng(testing::seed(7));
  std::normal_distribution<double> normal;
  std::vector<std::vector<double>> runs(50, std::vector<double>(400));
  for (auto& run : runs) {
    for (double& v : run) {
      v = 0.0;
      for (int d = 0; d < 3; ++d) v += std::pow(normal(rng), 2);
    }
  }
  // Statistic: the fraction of 400 independent steps whose ANEES (chi-square(150) / 50) lies in
  // its two-sided 95 % bounds, binomial(400, 0.95) / 400, sd 0.011. Within 0.03: false alarm
  // 0.44 % (exact binomial); a step's probability of 0.90 is caught 90 % of the time, 0.92 45 %.
  const double fraction = *fraction_inside(average_nees_over_runs(runs));
  EXPECT_NEAR(fraction, 0.95, 0.03);
  for (auto& run : runs) {
    for (double& v : run) v *= 2.0;
  }
  // Overconfident by a factor 2: almost never inside. A step inside needs 2 chi-square(150) / 50
  // below 3.72, chi-square(150) below 93, 3.8 sd under its mean by Wilson-Hilferty (probability
  // about 1e-4); 20 of 400 steps inside (a fraction of 0.05) then has probability far below 1e-9.
  EXPECT_LT(*fraction_inside(average_nees_over_runs(runs)), 0.05);
}

MonteCarloRun finished(int index, double mean_m, double runtime_s, std::vector<double> nees,
                       std::optional<double> segment) {
  MonteCarloRun run;
  run.index = index;
  run.metrics = RunMetrics{};
  run.metrics->errors.mean_m = mean_m;
  run.metrics->errors.final_m = 2.0 * mean_m;
  run.metrics->runtime_s = runtime_s;
  run.metrics->segments = {{"loop", segment}, {"canal", 1.0}};
  run.nees = std::move(nees);
  return run;
}

TEST(MonteCarlo, SummaryOfFinishedFailedAndMissingRuns) {
  MonteCarloRun failed;
  failed.index = 1;
  failed.failed = true;
  MonteCarloRun missing;
  missing.index = 3;
  const std::vector<MonteCarloRun> runs = {
      finished(0, 1.0, 0.5, {1.0, 2.0, 3.0}, 4.0), failed,
      finished(2, 3.0, std::numeric_limits<double>::quiet_NaN(), {5.0}, std::nullopt), missing};
  const MethodSummary s = summarise_runs("worldcentric", runs);
  EXPECT_EQ(s.method, "worldcentric");
  EXPECT_EQ(s.runs, 2);
  EXPECT_EQ(s.failed, 1);
  EXPECT_EQ(s.failed_runs, std::vector<int>{1});
  EXPECT_EQ(s.missing, 1);
  EXPECT_DOUBLE_EQ(*s.mean_error_m, 2.0);
  EXPECT_DOUBLE_EQ(*s.final_error_m, 4.0);
  EXPECT_DOUBLE_EQ(*s.anees, (1.0 + 2.0 + 3.0 + 5.0) / 4.0);  // over every run and scan
  ASSERT_EQ(s.nees.size(), 3u);
  EXPECT_EQ(s.nees[0].runs, 2);
  EXPECT_DOUBLE_EQ(s.nees[0].mean, 3.0);
  EXPECT_EQ(s.runtime_s, 0.5);  // the NaN runtime is left out
  ASSERT_EQ(s.segments.size(), 2u);
  EXPECT_EQ(s.segments[0].first, "loop");
  EXPECT_DOUBLE_EQ(*s.segments[0].second, 4.0);  // the run without a loop mean is skipped
  EXPECT_DOUBLE_EQ(*s.segments[1].second, 1.0);

  // Navigation-only methods have no NEES.
  const MethodSummary dr = summarise_runs("deadreckoning", {finished(0, 1.0, 0.1, {}, 1.0)});
  EXPECT_FALSE(dr.anees);
  EXPECT_FALSE(dr.nees_in_bounds_fraction);
  EXPECT_TRUE(dr.nees.empty());
  const MethodSummary none = summarise_runs("x", {});
  EXPECT_EQ(none.runs, 0);
  EXPECT_FALSE(none.mean_error_m);
}

TEST(MonteCarlo, QuantilesOfTheRunsMeanErrors) {
  std::vector<MonteCarloRun> runs;
  for (int r = 0; r < 21; ++r) runs.push_back(finished(r, 1.0 + r, 0.1, {}, 1.0));
  MonteCarloRun failed;
  failed.index = 21;
  failed.failed = true;
  runs.push_back(failed);
  const MethodSummary s = summarise_runs("robocentric", runs);
  ASSERT_TRUE(s.mean_error_quantiles_m);
  // 21 finished runs, mean errors 1..21: positions 1, 10 and 19 of the sorted sample.
  EXPECT_DOUBLE_EQ((*s.mean_error_quantiles_m)[0], 2.0);
  EXPECT_DOUBLE_EQ((*s.mean_error_quantiles_m)[1], 11.0);
  EXPECT_DOUBLE_EQ((*s.mean_error_quantiles_m)[2], 20.0);
  EXPECT_FALSE(summarise_runs("x", {failed}).mean_error_quantiles_m);
  EXPECT_DOUBLE_EQ(quantile({3.0, 1.0, 2.0, 4.0}, 0.5), 2.5);
  EXPECT_TRUE(std::isnan(quantile({}, 0.5)));
}

TEST(MonteCarlo, PairedDifferenceOverTheRunsBothFinished) {
  // Method a: 1, 2, 3, 4 m in runs 0-3; method b: a + 0.1, 0.2, 0.3 in runs 0-2 and run 3 failed.
  // The runs differ by metres, the methods by decimetres: pairing tells them apart.
  std::vector<MonteCarloRun> a, b;
  for (int r = 0; r < 4; ++r) a.push_back(finished(r, 1.0 + r, 0.1, {}, 1.0));
  for (int r = 0; r < 3; ++r) b.push_back(finished(r, 1.0 + r + 0.1 * (r + 1), 0.1, {}, 1.0));
  MonteCarloRun failed;
  failed.index = 3;
  failed.failed = true;
  b.push_back(failed);
  const MethodSummary sa = summarise_runs("a", a), sb = summarise_runs("b", b);
  const std::optional<PairedDifference> d = paired_difference(sb, sa);
  ASSERT_TRUE(d);
  EXPECT_EQ(d->reference, "a");
  EXPECT_EQ(d->runs, 3);
  EXPECT_NEAR(d->mean_m, 0.2, 1e-12);
  EXPECT_NEAR(d->sd_m, 0.1, 1e-12);
  // t(0.975; 2 DOF) = 4.302653: half width 4.302653 x 0.1 / sqrt(3).
  EXPECT_NEAR(d->ci95_upper_m - d->mean_m, 4.302653 * 0.1 / std::sqrt(3.0), 1e-6);
  EXPECT_NEAR(d->mean_m - d->ci95_lower_m, 4.302653 * 0.1 / std::sqrt(3.0), 1e-6);
  EXPECT_EQ(d->runs_lower, 0);
  EXPECT_FALSE(d->significant());  // 0.2 +- 0.248 m with three runs
  const std::optional<PairedDifference> back = paired_difference(sa, sb);
  ASSERT_TRUE(back);
  EXPECT_NEAR(back->mean_m, -0.2, 1e-12);
  EXPECT_EQ(back->runs_lower, 3);

  // Twenty runs of a constant 0.05 m offset plus small noise: significant.
  std::vector<MonteCarloRun> c, e;
  for (int r = 0; r < 20; ++r) {
    c.push_back(finished(r, 1.0 + 0.3 * r, 0.1, {}, 1.0));
    e.push_back(finished(r, 1.0 + 0.3 * r + 0.05 + 0.01 * ((r % 3) - 1), 0.1, {}, 1.0));
  }
  const std::optional<PairedDifference> offset =
      paired_difference(summarise_runs("e", e), summarise_runs("c", c));
  ASSERT_TRUE(offset);
  EXPECT_TRUE(offset->significant());
  EXPECT_GT(offset->ci95_lower_m, 0.04);
  // Fewer than two common runs: no interval.
  EXPECT_FALSE(paired_difference(summarise_runs("x", {a[0]}), sa));
}

TEST(MonteCarlo, ErrorSpreadOverTheRunsAtEachTime) {
  std::vector<MonteCarloRun> runs;
  for (int r = 0; r < 5; ++r) {
    MonteCarloRun run = finished(r, 1.0, 0.1, {}, 1.0);
    // Run r: error r at t = 0 and 10 r at t = 1; only runs 0-2 reach t = 2.
    run.errors = {{0.0, 1.0 * r}, {1.0, 10.0 * r}};
    if (r < 3) run.errors.push_back({2.0, 7.0});
    runs.push_back(run);
  }
  const MethodSummary s = summarise_runs("deadreckoning", runs);
  ASSERT_EQ(s.error_spread.size(), 3u);
  EXPECT_EQ(s.error_spread[1].t_s, 1.0);
  EXPECT_EQ(s.error_spread[1].runs, 5);
  EXPECT_DOUBLE_EQ(s.error_spread[1].mean_m, 20.0);
  EXPECT_DOUBLE_EQ(s.error_spread[1].p05_m, 2.0);  // h = 4 x 0.05 = 0.2 between 0 and 10
  EXPECT_DOUBLE_EQ(s.error_spread[1].p50_m, 20.0);
  EXPECT_DOUBLE_EQ(s.error_spread[1].p95_m, 38.0);
  EXPECT_EQ(s.error_spread[2].runs, 3);
  EXPECT_DOUBLE_EQ(s.error_spread[2].mean_m, 7.0);
  EXPECT_EQ(s.pooled_errors_m.size(), 13u);
}

TEST(MonteCarlo, ErrorHistogramsShareTheirBins) {
  MethodSummary a, b, empty;
  a.method = "a";
  a.pooled_errors_m = {0.0, 0.5, 1.0, 1.5, 3.9};
  b.method = "b";
  b.pooled_errors_m = {4.0, 2.0};
  empty.method = "empty";
  const std::vector<ErrorHistogram> h = error_histograms({a, b, empty}, 4);
  ASSERT_EQ(h.size(), 2u);  // the method without samples is left out
  EXPECT_EQ(h[0].edges_m, (std::vector<double>{0.0, 1.0, 2.0, 3.0, 4.0}));
  EXPECT_EQ(h[1].edges_m, h[0].edges_m);
  EXPECT_EQ(h[0].fractions, (std::vector<double>{0.4, 0.4, 0.0, 0.2}));
  EXPECT_EQ(h[1].fractions, (std::vector<double>{0.0, 0.0, 0.5, 0.5}));  // 4.0 in the last bin
  EXPECT_TRUE(error_histograms({empty}, 4).empty());
}

}  // namespace
}  // namespace msislab
