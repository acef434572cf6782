// Scoring an estimated trajectory against truth positions (GPS or simulation truth): planar
// distance at the truth's time stamps, the estimate interpolated, no alignment
// (docs/evaluation.md).
#pragma once

#include <Eigen/Core>
#include <optional>
#include <string>
#include <vector>

#include "eval/relative_pose_error.hpp"
#include "geometry/gaussian_pose.hpp"
#include "geometry/time_segment.hpp"

namespace msislab {

/// A truth position in the world frame.
struct PositionFix {
  double t_s = 0.0;
  Eigen::Vector2d p_world_m = Eigen::Vector2d::Zero();
};

/// The pose at t_s, interpolated linearly between the neighbouring samples (yaw along the shorter
/// arc). Requires a non-empty trajectory with t_s inside its time span.
Pose2 interpolate_pose(const std::vector<StampedPose>& trajectory, double t_s);

/// The position at t_s, interpolated linearly between the neighbouring fixes; the first or last
/// fix outside the track's time span. Requires a non-empty, time-ordered track.
Eigen::Vector2d interpolate_position(const std::vector<PositionFix>& track, double t_s);

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

/// Mean error inside a segment (t0_s is the first truth stamp); nullopt when no sample falls in it.
std::optional<double> segment_mean_error(const std::vector<ErrorSample>& errors, double t0_s,
                                         const TimeSegment& segment);

/// NEES e^T P^-1 e of each estimated pose against the truth interpolated at its time, with
/// e = pose_difference(estimate, truth) (angle wrapped). P is read from its upper triangle only, so
/// a covariance written to and read back from scans.csv gives the same value to the bit. Requires
/// a non-empty truth.
std::vector<double> pose_nees(const std::vector<StampedPose>& estimate,
                              const std::vector<StampedPose>& truth);

/// NEES of a relative-pose measurement z against the true relative pose in the directions whose
/// orthonormal rows A holds (3 x 3: all): e = A pose_difference(z, truth), e^T (A P_z A^T)^-1 e.
/// A scan match's consistency against the truth (matches.csv's nees).
double observed_nees(const GaussianPose2& z, const Eigen::MatrixXd& observed, const Pose2& truth);

/// The mean of the values; nullopt when there are none.
std::optional<double> mean_of(const std::vector<double>& values);

/// A scan match's translation with what the scale statistic needs: the two scans' times and the
/// reference scan's estimated yaw in the world frame.
struct MatchTranslation {
  double t_reference_s = 0.0;
  double t_s = 0.0;
  double yaw_reference_rad = 0.0;
  Eigen::Vector2d translation_reference_m =
      Eigen::Vector2d::Zero();  ///< scan in the reference's frame
};

/// The scale of scan-match translations against the truth positions (docs/formats.md,
/// metrics.json's consecutive_match_scale):
///   sum_i t_i . d_i / |d_i|  over  sum_i |d_i|,
/// d_i the true displacement between the two scans' times (positions interpolated), rotated
/// into the reference scan's frame by its estimated yaw. 1 when the matches neither shorten nor
/// lengthen the motion, below 1 when they shorten it. A match is left out when |d_i| is under
/// min_displacement_m (its direction is noise) or a time falls outside the truth or between fixes
/// more than max_fix_gap_s apart. nullopt when no match is left. GPS noise in d makes the figure
/// read low (docs/simulator.md, "Scan-match scale", has the measured bias).
std::optional<double> match_translation_scale(const std::vector<MatchTranslation>& matches,
                                              const std::vector<PositionFix>& truth,
                                              double min_displacement_m = 1.0,
                                              double max_fix_gap_s = 5.0);

/// How `msislab eval` put an estimate onto the truth before scoring it (docs/cli.md): its stamps
/// became t_s + t_offset_s, then every pose x became T_truth_estimate (+) x.
struct EstimateAlignment {
  std::string method = "none";     ///< "none" or "se2"
  std::optional<double> window_s;  ///< se2 fitted over the first window_s seconds of the overlap
  std::size_t positions = 0;       ///< matched positions the fit used; 0 for "none"
  double t_offset_s = 0.0;
  Pose2 T_truth_estimate;
};

/// What `msislab eval` adds to a run's figures.
struct EvalScores {
  EstimateAlignment alignment;
  std::optional<RelativePoseError> rpe;  ///< nullopt: the truth has no headings (GPS)
};

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
  std::optional<EvalScores> eval_scores;  ///< only from `msislab eval`
};

}  // namespace msislab
