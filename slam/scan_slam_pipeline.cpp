#include "slam/scan_slam_pipeline.hpp"

#include <iterator>

#include "slam/pose_graph_slam.hpp"
#include "slam/robocentric_slam.hpp"
#include "slam/trajectory_correction.hpp"
#include "slam/worldcentric_slam.hpp"

namespace msislab {

std::unique_ptr<ScanSlam> make_scan_slam(ScanSlamBackend backend, const SlamConfig& config,
                                         const GaussianPose2& start_world) {
  switch (backend) {
    case ScanSlamBackend::kRobocentric:
      return std::make_unique<RoboCentricSlam>(config.trajectory_slam, start_world);
    case ScanSlamBackend::kWorldcentric:
      return std::make_unique<WorldCentricSlam>(config.trajectory_slam, start_world);
    case ScanSlamBackend::kPoseGraph:
      return std::make_unique<PoseGraphSlam>(config.trajectory_slam.front_end,
                                             config.trajectory_slam.calibration, config.pose_graph,
                                             start_world);
  }
  return nullptr;
}

namespace {
/// The config whose dead reckoning builds a back end's scan motions: with the filters' DVL-scale
/// state on, the state carries the scale's uncertainty (correlated over every motion), so the
/// motions leave out the dead reckoning's considered one.
SlamConfig scan_motion_config(const SlamConfig& config) {
  SlamConfig out = config;
  if (config.trajectory_slam.calibration.dvl_scale) out.dead_reckoning.dvl_scale_sigma = 0.0;
  return out;
}
}  // namespace

bool slam_scans_are_dead_reckonings(const SlamConfig& config) {
  // (Conservative for the pose graph, whose scans are the dead reckoning's either way.)
  return scan_motion_config(config).dead_reckoning.dvl_scale_sigma ==
         config.dead_reckoning.dvl_scale_sigma;
}

std::vector<PlacedScan> build_placed_scans(const NavigationLog& navigation,
                                           const std::vector<BeamReadings>& beams,
                                           const SlamConfig& config, const ScanSlamSetup& setup) {
  ScanConfig builder;
  builder.beams_per_scan = setup.beams_per_revolution;
  builder.p_vehicle_sonar_m = setup.p_vehicle_sonar_m;
  std::vector<PlacedScan> scans = build_scans(beams, navigation, config.dead_reckoning,
                                              setup.p_vehicle_dvl_m, setup.start, builder);
  for (PlacedScan& placed : scans) {
    correct_footprint(placed.scan.points, config.footprint.table, config.footprint.line);
  }
  return scans;
}

ScanSlamEstimate run_scan_slam(ScanSlam& backend, const NavigationLog& navigation,
                               const std::vector<BeamReadings>& beams, const SlamConfig& config,
                               const ScanSlamSetup& setup) {
  ScanSlamEstimate out;
  // Dead reckoning (the paper's DVL + MRU EKF), and the scans it places (Sec. II).
  out.dead_reckoning =
      run_dead_reckoning(navigation, config.dead_reckoning, setup.p_vehicle_dvl_m, setup.start);
  // A back end without the DVL-scale state (the pose graph) keeps the considered uncertainty.
  out.scans = build_placed_scans(
      navigation, beams, backend.estimates_dvl_scale() ? scan_motion_config(config) : config,
      setup);
  // The back end, scan by scan (Sec. III-IV).
  for (const PlacedScan& placed : out.scans) {
    SlamStepStats step = backend.add_scan(placed.scan);
    std::vector<CalibrationEstimate> calibration = backend.calibration();
    if (!calibration.empty()) {
      out.calibration_history.push_back({placed.scan.t_s, std::move(calibration)});
    }
    out.matches.insert(out.matches.end(), std::make_move_iterator(step.matches.begin()),
                       std::make_move_iterator(step.matches.end()));
  }
  backend.finish();  // the pose graph's smoothing solve
  std::vector<StampedPose> dead_reckoning_at_scans;
  for (std::size_t i = 0; i < out.scans.size(); ++i) {
    dead_reckoning_at_scans.push_back(out.scans[i].centre_world);
    out.final_poses.push_back(backend.scan_pose_world(i));
  }
  out.totals = backend.totals();
  out.matches_downweighted = backend.matches_downweighted();
  out.calibration = backend.calibration();
  // The trajectory between scans follows dead reckoning from the latest corrected scan pose.
  const std::optional<std::vector<GaussianPose2>> online = backend.online_poses();
  out.online_poses = online ? *online : out.final_poses;
  out.trajectory =
      correct_trajectory(out.dead_reckoning.trajectory, dead_reckoning_at_scans, out.online_poses);
  if (online) {
    out.smoothed_trajectory =
        correct_trajectory(out.dead_reckoning.trajectory, dead_reckoning_at_scans, out.final_poses);
  }
  return out;
}

}  // namespace msislab
