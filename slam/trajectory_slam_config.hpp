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
struct TrajectoryFilterConfig {
  /// The joint update's cross-covariances between a step's matches (spIC's loadings on the newest
  /// scan's errors, shared_current_covariance). Off: taken as zero (for checks and studies).
  bool match_cross_covariance = true;
  /// Update every element instead of the loop's window (the same result at a higher cost; for
  /// checks and timing).
  bool update_whole_state = false;
};

struct TrajectorySlamConfig {
  ScanFrontEndConfig front_end;         ///< every back end's
  CalibrationStatesConfig calibration;  ///< every back end's
  TrajectoryFilterConfig filter;        ///< the filters'
};

}  // namespace msislab
