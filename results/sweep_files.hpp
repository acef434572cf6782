// sweep.csv of a sweep directory (docs/formats.md): one row per cell and method, the cell's
// overrides and the Monte Carlo figures of the method in that cell.
#pragma once

#include <optional>
#include <string>
#include <vector>

namespace msislab::results {

struct SweepRow {
  int cell = 0;
  std::vector<std::string> values;  ///< per swept key, the override's YAML text ('; ' for ', ')
  std::string method;
  int runs = 0;
  int failed = 0;
  std::optional<double> mean_error_m, p05_m, p50_m, p95_m;  ///< of the runs' mean errors
  std::optional<double> anees, nees_in_bounds_fraction;
  /// The paired difference of this method's per-run mean errors minus the reference's (the
  /// cell's first method; PairedDifference): empty for the reference itself.
  std::string paired_reference;
  std::optional<double> paired_difference_m, paired_ci95_lower_m, paired_ci95_upper_m;
  std::optional<int> paired_runs_lower;
  /// The summary's linearisation_* diagnostics (trajectory_slam.linearisation_samples > 0).
  std::optional<double> linearisation_observation, linearisation_inversion, linearisation_pose;
};

struct SweepTable {
  std::vector<std::string> keys;  ///< the swept keys: the columns after `cell`
  std::vector<SweepRow> rows;
};

/// Writes sweep.csv atomically: "cell,<keys...>,method,runs,failed,mean_error_m,
/// mean_error_p05_m,mean_error_p50_m,mean_error_p95_m,anees,nees_in_bounds_fraction,
/// paired_reference,paired_difference_m,paired_ci95_lower_m,paired_ci95_upper_m,
/// paired_runs_lower,linearisation_observation,linearisation_inversion,linearisation_pose"; an
/// empty field is a missing value.
void write_sweep_csv(const std::string& path, const SweepTable& table);
/// Reads it back; InputError naming the file and line for a malformed row.
SweepTable read_sweep_csv(const std::string& path);

}  // namespace msislab::results
