// The records every scan-based SLAM back end returns (slam/scan_slam.hpp): each candidate match
// as the back end saw it, what a step did, and the totals over a run.
#pragma once

#include <Eigen/Core>
#include <algorithm>
#include <array>
#include <cstddef>
#include <limits>
#include <string>
#include <vector>

#include "geometry/gaussian_pose.hpp"
#include "slam/match_validation.hpp"

namespace msislab {

/// Matches that did not reach the state, by reason, and those that reached it with a direction
/// left out (match_validation.hpp).
struct MatchRejectionCounts {
  std::array<int, kMatchRejectionReasons> rejected{};  ///< by MatchRejection (kNone stays 0)
  int direction_dropped = 0;  ///< accepted, observing 2 of the 3 directions

  void count(const ValidatedMatch& match);
};

/// One candidate match of a step as the filter saw it (a run's matches.csv): where it came from,
/// what spIC returned, what the state predicted, and what became of it.
struct MatchRecord {
  std::size_t scan = 0;       ///< k, the newest scan
  std::size_t reference = 0;  ///< j < k, the past scan matched against
  double distance_m = 0.0;    ///< the estimated distance between the two scans' centres
  bool valid = false;         ///< spIC converged with enough associations
  MatchRejection rejection = MatchRejection::kNone;  ///< kNone: it updated the state
  /// The observed directions as orthonormal rows (ValidatedMatch::observed): 3 x 3, or 2 x 3
  /// with a direction left out.
  Eigen::MatrixXd observed;
  int restarts = 0;  ///< spIC restarts the validation ran
  GaussianPose2 z;   ///< spIC's estimate of scan k in scan j's frame, and its covariance
  /// h(X) and H P H^T from the state the match was made from (the step's prediction, or for a
  /// later match of a sequential step the state the earlier ones left).
  GaussianPose2 predicted;
  /// The NIS of this match alone against that state, in its observed directions (NaN when it did
  /// not reach the gate). The joint update gates sets of matches; this is each one's own share.
  double nis = std::numeric_limits<double>::quiet_NaN();
};

/// What one step did.
struct SlamStepStats {
  int candidates = 0;
  int matched = 0;   ///< spIC valid
  int accepted = 0;  ///< passed the validation and the innovation gate and updated the state
  MatchRejectionCounts rejections;
  /// The scan could not be matched (too few finite points) or its motion was not finite; the step
  /// only predicted.
  bool skipped = false;
  int window_elements = 0;  ///< state elements touched by the largest update of the step
  bool compass_accepted = false;
  std::vector<MatchRecord> matches;  ///< every candidate, in the order they were matched

  /// Counts an update whose window held `elements` state elements.
  void note_window(std::size_t elements) {
    window_elements = std::max(window_elements, static_cast<int>(elements));
  }
};

/// The totals over a run.
/// A calibration parameter a back end estimates with the trajectory: its name (as in
/// metrics.json's diagnostics), its estimate and standard deviation after the last scan.
struct CalibrationEstimate {
  std::string name;
  double value = 0.0;
  double sigma = 0.0;
};

/// The calibration a back end estimates, as it stood after the scan at t_s (the estimates over
/// time, calibration.csv).
struct CalibrationSnapshot {
  double t_s = 0.0;
  std::vector<CalibrationEstimate> estimates;
};

struct SlamTotals {
  int scans = 0;
  int skipped = 0;
  int candidates = 0;
  int matched = 0;
  int accepted = 0;
  int compass_accepted = 0;
  MatchRejectionCounts rejections;
};

}  // namespace msislab
