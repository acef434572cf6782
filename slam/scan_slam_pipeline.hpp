// A whole scan-based SLAM run as one library call (paper Sec. II-IV): dead reckoning over the
// navigation log, the sonar's revolutions built into motion-compensated scans placed by it, every
// scan added to a back end (the two filters, the pose graph, or a user's own ScanSlam), and the
// full-rate trajectory corrected from the back end's scan poses. The inputs are read already (the
// file formats are io/'s); nothing is written and nothing given is changed.
#pragma once

#include <Eigen/Core>
#include <memory>
#include <optional>
#include <vector>

#include "geometry/gaussian_pose.hpp"
#include "slam/dead_reckoning.hpp"
#include "slam/scan_sequence.hpp"
#include "slam/scan_slam.hpp"
#include "slam/slam_config.hpp"

namespace msislab {

/// The back ends this library offers.
enum class ScanSlamBackend {
  kRobocentric,   ///< the paper's robocentric trajectory filter
  kWorldcentric,  ///< the world-centric one
  kPoseGraph,     ///< the same front end on a Ceres pose graph
};

/// A back end of that kind with the SLAM config's settings, starting at start_world.
std::unique_ptr<ScanSlam> make_scan_slam(ScanSlamBackend backend, const SlamConfig& config,
                                         const GaussianPose2& start_world);

/// Where the sensors sit and how a revolution is cut, besides the SLAM config.
struct ScanSlamSetup {
  StampedPose start;                                            ///< the vehicle at the start, world
  Eigen::Vector2d p_vehicle_dvl_m = Eigen::Vector2d::Zero();    ///< DVL lever arm, vehicle frame
  Eigen::Vector2d p_vehicle_sonar_m = Eigen::Vector2d::Zero();  ///< sonar head, vehicle frame
  int beams_per_revolution = 200;                               ///< beams in one 360 deg scan
};

/// What a run estimated. Scan i is scans[i]; its poses are in the vectors beside it.
struct ScanSlamEstimate {
  DeadReckoningResult dead_reckoning;  ///< the EKF over the whole log, full rate
  /// The scans as built, each placed by dead reckoning (centre_world: its dead-reckoning pose).
  std::vector<PlacedScan> scans;
  /// Each scan's corrected world pose as known when it was added (the online estimate); for the
  /// filters, which keep the whole trajectory, their final estimate (the same as final_poses).
  std::vector<GaussianPose2> online_poses;
  /// Each scan's world pose after the last scan (ScanSlam::scan_pose_world).
  std::vector<GaussianPose2> final_poses;
  /// The full-rate trajectory through online_poses (correct_trajectory).
  std::vector<StampedPose> trajectory;
  /// Where the back end tells the two apart (the pose graph): the trajectory through final_poses.
  std::optional<std::vector<StampedPose>> smoothed_trajectory;
  std::vector<MatchRecord> matches;  ///< every candidate match of every step, in order
  SlamTotals totals;
  std::optional<int> matches_downweighted;       ///< ScanSlam::matches_downweighted
  std::vector<CalibrationEstimate> calibration;  ///< ScanSlam::calibration after the last scan
  /// ScanSlam::calibration after every scan; empty when the back end estimates none.
  std::vector<CalibrationSnapshot> calibration_history;
};

/// Whether run_scan_slam's scans are build_placed_scans' with `config` as given, i.e. the dead
/// reckoning's own: not when the filters' DVL-scale state carries the scale's uncertainty, for
/// then their motions leave out the dead reckoning's (dead_reckoning.dvl_scale_sigma).
bool slam_scans_are_dead_reckonings(const SlamConfig& config);

/// The sonar's revolutions as motion-compensated scans placed by dead reckoning (Sec. II; the
/// scans run_scan_slam feeds its back end); with config.footprint's table, each scan's wall
/// points corrected for the beam's footprint (slam/beam_footprint.hpp).
std::vector<PlacedScan> build_placed_scans(const NavigationLog& navigation,
                                           const std::vector<BeamReadings>& beams,
                                           const SlamConfig& config, const ScanSlamSetup& setup);

/// Runs dead reckoning, builds the scans and feeds them to `backend` (fresh, started at
/// setup.start), then corrects the trajectory. The back end is left holding the run's state.
ScanSlamEstimate run_scan_slam(ScanSlam& backend, const NavigationLog& navigation,
                               const std::vector<BeamReadings>& beams, const SlamConfig& config,
                               const ScanSlamSetup& setup);

}  // namespace msislab
