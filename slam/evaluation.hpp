// Scoring an estimated trajectory against truth positions (GPS or simulation truth): planar
// distance at the truth's time stamps, the estimate interpolated, no alignment
// (docs/evaluation.md).
#pragma once

#include <Eigen/Core>
#include <optional>
#include <string>
#include <vector>

#include "slam/gaussian_pose.hpp"

namespace msislab {

/// A truth position in the world frame.
struct PositionFix {
  double t_s = 0.0;
  Eigen::Vector2d p_world_m = Eigen::Vector2d::Zero();
};

/// The pose at t_s, interpolated linearly between the neighbouring samples (yaw along the shorter
/// arc). Requires a non-empty trajectory with t_s inside its time span.
Pose2 interpolate_pose(const std::vector<StampedPose>& trajectory, double t_s);

struct ErrorSample {
  double t_s = 0.0;
  double error_m = 0.0;
};

/// Position error at every truth stamp inside the estimate's time span.
std::vector<ErrorSample> position_errors(const std::vector<StampedPose>& estimate,
                                         const std::vector<PositionFix>& truth);

struct ErrorStats {
  std::size_t count = 0;
  double mean_m = 0.0;
  double rmse_m = 0.0;
  double median_m = 0.0;
  double max_m = 0.0;
  double final_m = 0.0;  ///< error at the last truth stamp
};

/// Statistics of a set of errors; nullopt when it is empty.
std::optional<ErrorStats> error_stats(const std::vector<ErrorSample>& errors);

/// A named time window, in seconds from the first truth stamp: [begin_s, end_s).
struct TimeSegment {
  std::string name;
  double begin_s = 0.0;
  double end_s = 0.0;
};

/// Mean error inside a segment (t0_s is the first truth stamp); nullopt when no sample falls in it.
std::optional<double> segment_mean_error(const std::vector<ErrorSample>& errors, double t0_s,
                                         const TimeSegment& segment);

/// NEES e^T P^-1 e of each estimated pose against the truth interpolated at its time, with
/// e = pose_difference(estimate, truth) (angle wrapped). P is read from its upper triangle only, so
/// a covariance written to and read back from scans.csv gives the same value to the bit. Requires
/// a non-empty truth.
std::vector<double> pose_nees(const std::vector<StampedPose>& estimate,
                              const std::vector<StampedPose>& truth);

/// The mean of the values; nullopt when there are none.
std::optional<double> mean_of(const std::vector<double>& values);

/// What metrics.json holds (docs/formats.md).
struct RunMetrics {
  std::string method;
  std::string truth;  ///< "gps" or "simulation"
  ErrorStats errors;
  std::vector<std::pair<std::string, std::optional<double>>> segments;  ///< name -> mean error
  std::vector<TimeSegment> segment_windows;  ///< the windows behind `segments`, same order
  int scans = 0;
  int matches_accepted = 0;
  double runtime_s = 0.0;
  std::optional<double> anees;  ///< only with simulation truth
  /// Method-specific figures (e.g. DVL samples used, mean innovation NIS), name -> value.
  std::vector<std::pair<std::string, double>> diagnostics;
};

}  // namespace msislab
