// Readers of the files that `msislab run` and `msislab montecarlo` write (docs/formats.md) that
// only `msislab plot` reads: map.ply and a Monte Carlo nees.csv (scans.csv, metrics.json and a
// run's nees.csv are read back by io/results).
// Strict like every reader here: the exact header, the field count, finite numbers; any other line
// is an InputError "file:line: what".
#pragma once

#include <Eigen/Core>
#include <string>
#include <vector>

#include "eval/monte_carlo.hpp"

namespace msislab::results {

/// The vertices (x, y) of a PLY point cloud such as map.ply (io/ply: ASCII or binary); z and
/// other properties are ignored.
std::vector<Eigen::Vector2d> read_points_ply(const std::string& path);

/// One row of a Monte Carlo nees.csv: the NEES of scan `scan` averaged over `runs` runs, with the
/// two-sided 95% chi-square bounds of that average.
struct NeesRow {
  std::string method;
  long long scan = 0;
  long long runs = 0;
  double mean_nees = 0.0;
  double lower = 0.0;
  double upper = 0.0;
};

/// Reads nees.csv (header "method,scan,runs,mean_nees,lower,upper"); scans increase per method.
std::vector<NeesRow> read_montecarlo_nees(const std::string& path);

/// errors.csv of a Monte Carlo directory (write_error_spread_csv); times increase per method.
struct ErrorSpreadRow {
  std::string method;
  ErrorSpread spread;
};
std::vector<ErrorSpreadRow> read_error_spread_csv(const std::string& path);

/// error_histogram.csv of a Monte Carlo directory (write_error_histogram_csv).
std::vector<ErrorHistogram> read_error_histogram_csv(const std::string& path);

}  // namespace msislab::results
