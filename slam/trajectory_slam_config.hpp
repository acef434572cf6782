// The settings of trajectory SLAM, read from the `trajectory_slam` section of a SLAM config
// (docs/formats.md): the scan front end's, which every back end shares, the calibration states',
// which the pose graph estimates too, and the filters' own. The section's
// linearisation_samples is a study's switch, not a setting of the filter: it is
// SlamConfig::linearisation_samples (slam/slam_config.hpp).
#pragma once

#include "slam/calibration_states_config.hpp"
#include "slam/scan_front_end_config.hpp"

namespace msislab {

/// What only the two filters read.
/// The errors of a scan that its matches share, held in the filter's state.
enum class ScanSharedErrors {
  kNone,             ///< none: each match's covariance is its own noise
  kMotion,           ///< each half-scan's motion error xi ~ N(0, I), loaded exactly (spIC's M)
  kMotionAndPoints,  ///< and each scan's rigid error for its points' reading noise
};

struct TrajectoryFilterConfig {
  /// The joint update's cross-covariances between a step's matches (spIC's loadings on the newest
  /// scan's errors, shared_current_covariance). Off: taken as zero (for checks and studies).
  bool match_cross_covariance = true;
  /// Update every element instead of the loop's window (the same result at a higher cost; for
  /// checks and timing).
  bool update_whole_state = false;
  /// Which of each scan's own errors the state holds, shared by every match of the scan
  /// (docs/trajectory_slam.md, "Scan registration errors"). Not in the state, a match's errors
  /// are taken as its own, which a scan reused across steps makes overconfident where several
  /// scans match it and underconfident along a chain of consecutive matches.
  ScanSharedErrors scan_shared_errors = ScanSharedErrors::kNone;
};

struct TrajectorySlamConfig {
  ScanFrontEndConfig front_end;         ///< every back end's
  CalibrationStatesConfig calibration;  ///< every back end's
  TrajectoryFilterConfig filter;        ///< the filters'
};

}  // namespace msislab
