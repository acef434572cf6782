// The files of a result directory (docs/formats.md): trajectory.tum and metrics.json.
#pragma once

#include <string>
#include <vector>

#include "slam/evaluation.hpp"
#include "slam/scan_sequence.hpp"

namespace msislab::io {

/// Writes a trajectory as TUM (z = -depth_m, planar yaw as a quaternion), atomically.
void write_trajectory_tum(const std::string& path, const std::vector<StampedPose>& trajectory,
                          double depth_m);

/// Writes metrics.json atomically. `dataset_dir` is recorded so `msislab eval` can find the truth.
void write_metrics_json(const std::string& path, const RunMetrics& metrics,
                        const std::string& dataset_dir);

/// scans.csv: one row per scan, "t_s,x_m,y_m,yaw_rad,cov_xx,cov_xy,cov_xyaw,cov_yy,cov_yyaw,
/// cov_yawyaw,points" (the scan frame's world pose and its covariance), atomically.
void write_scans_csv(const std::string& path, const std::vector<PlacedScan>& scans);

/// An ASCII PLY point cloud (z = 0), atomically.
void write_points_ply(const std::string& path, const std::vector<Eigen::Vector2d>& points_m);

/// JSON text of a number: shortest round-trip form, null when not finite.
std::string json_number(double value);
/// JSON string literal with escapes.
std::string json_string(const std::string& text);

}  // namespace msislab::io
