// Runs robocentric SLAM, the paper's method, through the installed library on a survey simulated
// in memory: a loop in a square basin, DVL and MRU logs with their noise, and every sonar beam's
// returns. The data come from msislab's simulator here; a user's own logs would fill the same two
// records (NavigationLog, BeamReadings). One call, run_scan_slam, runs dead reckoning, builds the
// motion-compensated scans, feeds them to the back end and corrects the trajectory. Prints the
// mean position error of dead reckoning and of the SLAM against the truth; exits 1 when no match
// was accepted or the SLAM errs by 1.5 m or more on average.
#include <cmath>
#include <cstdio>
#include <vector>

#include "eval/evaluation.hpp"
#include "geometry/calibration.hpp"
#include "sim/msis.hpp"
#include "sim/navigation_sensors.hpp"
#include "sim/random.hpp"
#include "sim/scene.hpp"
#include "sim/scene_builder.hpp"
#include "sim/vehicle.hpp"
#include "slam/beam_segmentation.hpp"
#include "slam/scan_slam_pipeline.hpp"

namespace {

using namespace msislab;

/// DVL and heading readings in the vehicle frame, as a user's logs would give them.
NavigationLog navigation_of(const sim::VehicleTrajectory& truth, const sim::Scene& scene,
                            double depth_m) {
  const sim::DvlConfig dvl;  // the St. Pere DVL's noise, dropouts and mount
  const sim::MruConfig mru;  // the St. Pere MRU's heading noise, drift and mount
  NavigationLog log;
  for (const sim::DvlSample& s : sim::simulate_dvl(truth, dvl, scene, depth_m, 11)) {
    if (!s.bottom_lock) {
      ++log.dvl_rows_without_bottom_lock;
      continue;
    }
    log.dvl.push_back({s.t_s, R_vehicle_dvl(dvl.mount) * s.v_dvl_mps});
  }
  for (const sim::MruSample& s : sim::simulate_mru(truth, mru, 12)) {
    log.heading.push_back({s.t_s, vehicle_yaw_from_mru(s.yaw_mru_deg, mru.mount)});
  }
  return log;
}

/// Every beam of the survey with the returns segmented from its intensity profile.
std::vector<BeamReadings> beams_of(const sim::VehicleTrajectory& truth, const sim::Scene& scene,
                                   const sim::SonarConfig& sonar,
                                   const SegmentationConfig& segmentation) {
  const sim::MsisModel model(scene, sonar, 1.0);
  std::vector<BeamReadings> beams;
  for (const sim::BeamSlot& slot : sim::beam_schedule(sonar, truth.start_s(), truth.end_s())) {
    sim::Rng rng(1000 + slot.index);
    const sim::RenderedBeam beam = model.render(slot, truth, rng);
    BeamReadings readings{slot.t_s, {}};
    const double bearing_rad = sonar_bearing_in_vehicle(slot.transducer_angle_rad, sonar.mount);
    for (const double range_m : segment_profile(beam.intensity, sonar.bin_m, segmentation)) {
      readings.readings.push_back({slot.t_s, range_m, bearing_rad, segmentation.sigma_range_m,
                                   segmentation.sigma_bearing_rad});
    }
    beams.push_back(std::move(readings));
  }
  return beams;
}

/// Mean position error against the truth (eval/: the truth at 1 Hz, the trajectory interpolated).
double mean_error_m(const std::vector<StampedPose>& trajectory,
                    const sim::VehicleTrajectory& truth) {
  std::vector<PositionFix> fixes;
  for (double t_s = truth.start_s(); t_s <= truth.end_s(); t_s += 1.0) {
    fixes.push_back({t_s, truth.at(t_s).pose.translation()});
  }
  return error_stats(position_errors(trajectory, fixes))->mean_m;
}

}  // namespace

int main() {
  // The scene: a 60 m square basin with a channel leaving its east side, 8 m deep.
  sim::MeshBuilder builder;
  const std::uint32_t walls = builder.group("walls", 0.6f, 0.3f);
  const std::uint32_t bottom = builder.group("bottom", 0.01f, 0.1f);
  sim::BasinProfile profile;
  profile.z_bottom_m = -8.0;
  sim::add_basin(builder, sim::channel_basin_outline(sim::ChannelBasin{}), profile, walls, bottom);
  const sim::Scene scene(builder.mesh(), sim::Material{"surface", 0.0f, 0.9f});

  // The survey: one loop 15 m inside the basin's walls at 0.25 m/s (about 8 minutes).
  sim::VehicleConfig vehicle;
  vehicle.speed_mps = 0.25;
  vehicle.path_m = {{0, -15}, {15, -15}, {15, 15}, {-15, 15}, {-15, -15}, {0, -15}};
  const sim::VehicleTrajectory truth = sim::follow_path(vehicle);

  SlamConfig config;  // the paper's settings, msislab's defaults
  const sim::SonarConfig sonar;
  const NavigationLog navigation = navigation_of(truth, scene, vehicle.depth_m);
  const std::vector<BeamReadings> beams = beams_of(truth, scene, sonar, config.segmentation);

  // The method: robocentric SLAM from the true start pose, known to 0.1 m and 1 degree.
  ScanSlamSetup setup;
  setup.start = {truth.start_s(),
                 {truth.at(truth.start_s()).pose,
                  Eigen::Vector3d(0.01, 0.01, std::pow(M_PI / 180.0, 2)).asDiagonal()}};
  setup.p_vehicle_dvl_m = {0.0, 0.0};
  setup.p_vehicle_sonar_m = {sonar.mount.x_m, sonar.mount.y_m};
  setup.beams_per_revolution = sonar.steps_per_revolution;
  const std::unique_ptr<ScanSlam> slam =
      make_scan_slam(ScanSlamBackend::kRobocentric, config, setup.start.pose);
  const ScanSlamEstimate estimate = run_scan_slam(*slam, navigation, beams, config, setup);

  const double dead_reckoning_m = mean_error_m(estimate.dead_reckoning.trajectory, truth);
  const double slam_m = mean_error_m(estimate.trajectory, truth);
  std::printf("%zu beams, %zu scans, %d of %d candidate matches accepted\n", beams.size(),
              estimate.scans.size(), estimate.totals.accepted, estimate.totals.candidates);
  std::printf("mean position error: dead reckoning %.2f m, robocentric SLAM %.2f m\n",
              dead_reckoning_m, slam_m);
  return estimate.totals.accepted > 0 && slam_m < 1.5 ? 0 : 1;
}
