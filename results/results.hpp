// The files of a result directory (docs/formats.md): trajectory.tum, metrics.json, scans.csv,
// matches.csv, nees.csv, calibration.csv and map.ply.
#pragma once

#include <string>
#include <vector>

#include "eval/evaluation.hpp"
#include "io/json.hpp"
#include "slam/scan_sequence.hpp"
#include "slam/trajectory_slam.hpp"

namespace msislab::results {

/// Writes a trajectory as TUM (z = -depth_m, planar yaw as a quaternion), atomically.
void write_trajectory_tum(const std::string& path, const std::vector<StampedPose>& trajectory,
                          double depth_m);

/// Writes metrics.json atomically. `dataset_dir` is recorded so `msislab eval` can find the truth;
/// `truth_file` (written only when not empty) names a TUM truth given to `msislab eval --truth`.
void write_metrics_json(const std::string& path, const RunMetrics& metrics,
                        const std::string& dataset_dir, const std::string& truth_file = "");

/// metrics.json: the metrics and where their truth came from.
struct StoredMetrics {
  RunMetrics metrics;       ///< runtime_s and diagnostics written as null read back as NaN
  std::string dataset_dir;  ///< empty when null
  std::string truth_file;   ///< empty when absent
};
void to_json(io::Json& json, const StoredMetrics& stored);
void from_json(const io::JsonObject& json, StoredMetrics& stored);
StoredMetrics read_metrics_json(const std::string& path);

/// scans.csv: one row per scan, "t_s,x_m,y_m,yaw_rad,cov_xx,cov_xy,cov_xyaw,cov_yy,cov_yyaw,
/// cov_yawyaw,points" (the scan frame's world pose and its covariance), atomically.
void write_scans_csv(const std::string& path, const std::vector<PlacedScan>& scans);

/// scans.csv read back: each scan's time and world pose with its covariance.
std::vector<StampedPose> read_scans_csv(const std::string& path);

/// One row of matches.csv: a candidate match of a trajectory SLAM step, the times of its two
/// scans and, when the dataset has pose truth, the true pose of the newest scan in the reference
/// scan's frame and the match's NEES against it in its observed directions.
struct MatchRow {
  double t_s = 0.0;            ///< the newest scan's time
  double t_reference_s = 0.0;  ///< the reference scan's time
  MatchRecord record;
  bool has_truth = false;
  Pose2 truth;
  double nees = 0.0;  ///< A (z - truth) against A cov(z) A^T, when has_truth and the match is valid
};
/// matches.csv: one row per candidate match in the order they were made, atomically. Header:
/// "t_s,scan,reference,t_reference_s,distance_m,outcome,observed,restarts,nis,z_x_m,z_y_m,
/// z_yaw_rad,z_cov_xx,z_cov_xy,z_cov_xyaw,z_cov_yy,z_cov_yyaw,z_cov_yawyaw,pred_x_m,pred_y_m,
/// pred_yaw_rad,pred_cov_xx,pred_cov_xy,pred_cov_xyaw,pred_cov_yy,pred_cov_yyaw,pred_cov_yawyaw,
/// true_x_m,true_y_m,true_yaw_rad,nees"; outcome is "accepted" or the rejection's name; a value
/// that does not exist (nis when the gate was not reached, truth) is an empty field.
void write_matches_csv(const std::string& path, const std::vector<MatchRow>& rows);

/// calibration.csv: the calibration a back end estimated, after every scan: "t_s" then, per
/// parameter, its name and name_sigma (the names of the first snapshot; every snapshot must have
/// them in that order), atomically.
void write_calibration_csv(const std::string& path,
                           const std::vector<CalibrationSnapshot>& snapshots);

/// One row of nees.csv: the NEES of scan `scan` (0-based) at time t_s.
struct NeesSample {
  double t_s = 0.0;
  double nees = 0.0;
};
/// nees.csv: "scan,t_s,nees", one row per scan in order, atomically.
void write_nees_csv(const std::string& path, const std::vector<NeesSample>& samples);

/// errors.csv of a Monte Carlo run: "t_s,error_m", the position error once a second (the first
/// truth stamp at or after each whole second from the first one), t_s from the first truth stamp.
void write_errors_csv(const std::string& path, const std::vector<ErrorSample>& errors,
                      double t_first_truth_s);
std::vector<ErrorSample> read_errors_csv(const std::string& path);
/// nees.csv read back (the scan column must count 0, 1, 2, ...).
std::vector<NeesSample> read_nees_csv(const std::string& path);

/// An ASCII PLY point cloud (z = 0), atomically.
void write_points_ply(const std::string& path, const std::vector<Eigen::Vector2d>& points_m);

}  // namespace msislab::results
