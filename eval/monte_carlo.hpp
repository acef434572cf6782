// Monte Carlo consistency statistics over repeated seeded runs of one method: the per-scan NEES
// averaged over the runs with its two-sided chi-square bounds (field-notes, NEES: N times the
// average of N 3-DOF NEES is chi-square with 3N DOF), and the summary of the runs' metrics.
#pragma once

#include <array>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "eval/evaluation.hpp"

namespace msislab {

/// The NEES of one scan index averaged over the runs that reached it, with the two-sided bounds of
/// that average for that number of runs.
struct AveragedNees {
  int runs = 0;
  double mean = 0.0;
  double lower = 0.0;
  double upper = 0.0;
  bool inside() const { return mean >= lower && mean <= upper; }
};

/// nees_by_run[r][k]: the NEES of scan k in run r (runs may have different scan counts). Scan k is
/// averaged over the runs that have it, and bounded by average_chi2_bounds(runs, dof, alpha).
std::vector<AveragedNees> average_nees_over_runs(
    const std::vector<std::vector<double>>& nees_by_run, int dof = 3, double alpha = 0.05);

/// The fraction of the scan indices whose average lies inside its bounds; nullopt when none.
std::optional<double> fraction_inside(const std::vector<AveragedNees>& steps);

/// What one Monte Carlo run left for one method.
struct MonteCarloRun {
  int index = 0;                      ///< r: the run used seed = scenario seed + r
  std::optional<RunMetrics> metrics;  ///< present when the run finished
  bool failed = false;
  std::vector<double> nees;         ///< per scan (SLAM methods with pose truth)
  std::vector<ErrorSample> errors;  ///< position error, t_s from the first truth stamp
};

/// The spread over the runs of the position error at one time (seconds from the first truth
/// stamp): its mean and 5, 50, 95 % quantiles over the runs that have a sample there.
struct ErrorSpread {
  double t_s = 0.0;
  int runs = 0;
  double mean_m = 0.0;
  double p05_m = 0.0;
  double p50_m = 0.0;
  double p95_m = 0.0;
};

/// A paired comparison of two methods' mean errors over the runs both finished: for each such run
/// r, d_r = (method's mean error) - (reference's mean error), then the mean of the d_r with its
/// two-sided 95 % confidence interval (Student t with runs - 1 DOF). The pairing takes out the
/// run-to-run spread both methods share (the same simulated data), so a difference far smaller
/// than either method's spread can still be told from zero.
struct PairedDifference {
  std::string reference;  ///< the method subtracted
  int runs = 0;           ///< runs both finished
  double mean_m = 0.0;    ///< mean of d_r: below 0, the method's errors are smaller
  double sd_m = 0.0;      ///< sample standard deviation of d_r
  double ci95_lower_m = 0.0;
  double ci95_upper_m = 0.0;
  int runs_lower = 0;  ///< runs where the method's mean error is below the reference's
  /// Zero lies outside the interval: the two differ beyond the Monte Carlo noise.
  bool significant() const { return ci95_lower_m > 0.0 || ci95_upper_m < 0.0; }
};

/// The runs of one method summarised.
struct MethodSummary {
  std::string method;
  int runs = 0;    ///< finished
  int failed = 0;  ///< recorded as failed
  std::vector<int> failed_runs;
  int missing = 0;                     ///< neither finished nor failed (an unfinished shard)
  std::optional<double> mean_error_m;  ///< mean over the runs of each run's mean error
  /// The 5, 50 and 95 % quantiles over the runs of each run's mean error (quantile()).
  std::optional<std::array<double, 3>> mean_error_quantiles_m;
  std::optional<double> final_error_m;            ///< mean over the runs of each run's final error
  std::optional<double> anees;                    ///< mean over every run and scan of the scan NEES
  std::optional<double> nees_in_bounds_fraction;  ///< fraction_inside(nees)
  std::vector<AveragedNees> nees;                 ///< per scan index
  /// Segment name -> mean over the runs of the segment's mean error (runs where it is null
  /// skipped).
  std::vector<std::pair<std::string, std::optional<double>>> segments;
  /// metrics.json's diagnostics, each the mean over the finished runs with a finite value, in
  /// first-seen order.
  std::vector<std::pair<std::string, double>> diagnostics;
  double runtime_s = 0.0;                 ///< sum of the runs' runtime_s
  std::vector<ErrorSpread> error_spread;  ///< per time the runs sampled, in time order
  std::vector<double> pooled_errors_m;    ///< every run's error samples, for the distribution
  /// (run index, mean error) of every finished run with a mean error, in run order, for
  /// paired_difference (not in summary.json).
  std::vector<std::pair<int, double>> run_mean_errors_m;
  /// Against the Monte Carlo directory's first method (its own row has none).
  std::optional<PairedDifference> paired;
};

/// The paired difference of method's mean errors minus reference's over the runs both have;
/// nullopt with fewer than 2 such runs.
std::optional<PairedDifference> paired_difference(const MethodSummary& method,
                                                  const MethodSummary& reference);

/// A histogram of each method's pooled position errors on bins shared by all the methods.
struct ErrorHistogram {
  std::string method;
  std::vector<double> edges_m;    ///< bins + 1 increasing edges from 0
  std::vector<double> fractions;  ///< of the method's samples in each bin (the last one closed)
};

/// `bins` equal bins from 0 to the largest pooled error of any method; methods without samples
/// are left out.
std::vector<ErrorHistogram> error_histograms(const std::vector<MethodSummary>& methods,
                                             int bins = 40);

/// Summarises the runs in the order given (by run index, so the sums do not depend on which run
/// finished first).
MethodSummary summarise_runs(const std::string& method, const std::vector<MonteCarloRun>& runs);

}  // namespace msislab
