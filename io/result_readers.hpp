// Readers of the files that `msislab run` and `msislab montecarlo` write (docs/formats.md), for
// `msislab plot`: scans.csv, map.ply, the keys of metrics.json a figure needs, and nees.csv.
// Strict like every reader here: the exact header, the field count, finite numbers; any other line
// is an InputError "file:line: what".
#pragma once

#include <Eigen/Core>
#include <string>
#include <vector>

namespace msislab::io {

/// One row of scans.csv: a scan's world pose and its 3x3 covariance (x, y, yaw).
struct ScanRow {
  double t_s = 0.0;
  double x_m = 0.0;
  double y_m = 0.0;
  double yaw_rad = 0.0;
  Eigen::Matrix3d cov = Eigen::Matrix3d::Zero();
  long long points = 0;
};

std::vector<ScanRow> read_scan_rows(const std::string& path);

/// The vertices (x, y) of an ASCII PLY point cloud such as map.ply; z and other properties are
/// ignored. Binary PLY is an error (msislab writes ASCII).
std::vector<Eigen::Vector2d> read_points_ply(const std::string& path);

/// The keys of metrics.json the figures use.
struct MetricsInfo {
  std::string method;
  std::string truth;    ///< "simulation" or "gps"
  std::string dataset;  ///< absolute dataset directory; empty when the file has no such key
};

/// Reads metrics.json (JSON is read as YAML); `method` is required, unknown keys are ignored.
MetricsInfo read_metrics_info(const std::string& path);

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

}  // namespace msislab::io
