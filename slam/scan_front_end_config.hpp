// The settings of the scan front end every back end shares (slam/scan_front_end.hpp): which past
// scans a new one is matched against, spIC and the checks a match passes, the gates on matches and
// on the compass, and how a step's updates are made. Read from the `trajectory_slam` section of a
// SLAM config (docs/formats.md), where they sit beside the filters' own keys.
#pragma once

#include "slam/match_validation.hpp"
#include "slam/scan_matching.hpp"

namespace msislab {

struct ScanFrontEndConfig {
  double association_distance_m = 10.0;  ///< gamma: match past scans closer than this (m)
  int max_matches_per_scan = 3;          ///< the nearest candidates first
  int min_scan_gap = 1;  ///< match scans at least this many steps back (1: the previous one too)
  ScanMatchConfig matching;
  MatchValidationConfig validation;     ///< checks a match passes before the update
  double innovation_gate_chi2 = 11.34;  ///< 3 DOF, 99%: inconsistent matches are rejected
  /// Update each scan's world heading with the MRU's absolute heading (a relative chain forgets
  /// that the compass bounds the heading error; docs/trajectory_slam.md).
  bool compass_updates = true;
  double compass_gate_chi2 = 6.63;  ///< 1 DOF, 99%
  /// Update a step's matches together (paper Eq. 8): every match made from the step's prediction
  /// and the jointly compatible ones stacked in one update. Off: one match after the other, each
  /// made from the state the previous one left.
  bool joint_update = false;
  int iekf_iterations = 5;  ///< relinearisations of each update (1 = plain EKF)
};

}  // namespace msislab
