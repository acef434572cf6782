// The files of a result directory (docs/formats.md): trajectory.tum, metrics.json, scans.csv,
// nees.csv and map.ply.
#pragma once

#include <string>
#include <vector>

#include "slam/evaluation.hpp"
#include "slam/scan_sequence.hpp"

namespace msislab::io {

/// Writes a trajectory as TUM (z = -depth_m, planar yaw as a quaternion), atomically.
void write_trajectory_tum(const std::string& path, const std::vector<StampedPose>& trajectory,
                          double depth_m);

/// Writes metrics.json atomically. `dataset_dir` is recorded so `msislab eval` can find the truth;
/// `truth_file` (written only when not empty) names a TUM truth given to `msislab eval --truth`.
void write_metrics_json(const std::string& path, const RunMetrics& metrics,
                        const std::string& dataset_dir, const std::string& truth_file = "");

/// metrics.json read back.
struct StoredMetrics {
  RunMetrics metrics;       ///< runtime_s and diagnostics written as null read back as NaN
  std::string dataset_dir;  ///< empty when null
};
StoredMetrics read_metrics_json(const std::string& path);

/// scans.csv: one row per scan, "t_s,x_m,y_m,yaw_rad,cov_xx,cov_xy,cov_xyaw,cov_yy,cov_yyaw,
/// cov_yawyaw,points" (the scan frame's world pose and its covariance), atomically.
void write_scans_csv(const std::string& path, const std::vector<PlacedScan>& scans);

/// scans.csv read back: each scan's time and world pose with its covariance.
std::vector<StampedPose> read_scans_csv(const std::string& path);

/// One row of nees.csv: the NEES of scan `scan` (0-based) at time t_s.
struct NeesSample {
  double t_s = 0.0;
  double nees = 0.0;
};
/// nees.csv: "scan,t_s,nees", one row per scan in order, atomically.
void write_nees_csv(const std::string& path, const std::vector<NeesSample>& samples);
/// nees.csv read back (the scan column must count 0, 1, 2, ...).
std::vector<NeesSample> read_nees_csv(const std::string& path);

/// An ASCII PLY point cloud (z = 0), atomically.
void write_points_ply(const std::string& path, const std::vector<Eigen::Vector2d>& points_m);

/// JSON text of a number: shortest round-trip form, null when not finite.
std::string json_number(double value);
/// JSON string literal with escapes.
std::string json_string(const std::string& text);

}  // namespace msislab::io
