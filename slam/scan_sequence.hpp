// From a run's sonar readings and navigation to its sequence of scans: dead reckoning sampled at
// every beam time (motion since the previous beam, with covariance, by stochastic cloning) feeds
// the scan builder. What the trajectory SLAM consumes (paper Sec. II).
#pragma once

#include <vector>

#include "slam/dead_reckoning.hpp"
#include "slam/scan_builder.hpp"

namespace msislab {

/// The readings of one beam (possibly none) at its time.
struct BeamReadings {
  double t_s = 0.0;
  std::vector<SonarReading> readings;
};

struct PlacedScan {
  Scan scan;
  StampedPose centre_world;  ///< dead-reckoning pose of the scan frame in the world
};

/// Builds every complete revolution of beams taken at or after initial.t_s (earlier beams, when
/// there is no navigation yet, are skipped; a last incomplete revolution is dropped). Each scan's
/// motion (from the previous scan frame; the first: from the start pose) comes from the dead
/// reckoning with its exact covariance (a clone from centre to centre).
std::vector<PlacedScan> build_scans(const std::vector<BeamReadings>& beams,
                                    const NavigationLog& navigation,
                                    const DeadReckoningConfig& dead_reckoning,
                                    const Eigen::Vector2d& p_vehicle_dvl_m,
                                    const StampedPose& initial, const ScanConfig& config);

/// Every scan point placed in the world through its scan's pose.
std::vector<Eigen::Vector2d> world_points(const std::vector<PlacedScan>& scans);

}  // namespace msislab
