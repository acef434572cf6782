#include "app/run_method.hpp"

#include <algorithm>
#include <chrono>
#include <iostream>
#include <iterator>

#include "app/external_method.hpp"
#include "app/method_result.hpp"
#include "io/input_error.hpp"
#include "slam/calibration_update.hpp"
#include "slam/dead_reckoning.hpp"
#include "slam/linearisation_probe.hpp"
#include "slam/pose_graph_slam.hpp"
#include "slam/scan_slam_pipeline.hpp"
#include "slam/trajectory_slam.hpp"

namespace msislab::app {

namespace {

/// The scans placed at the given world poses (one per scan), for the files and the scores that
/// show the corrected map.
std::vector<PlacedScan> placed_at(const std::vector<PlacedScan>& scans,
                                  const std::vector<GaussianPose2>& poses_world) {
  std::vector<PlacedScan> placed = scans;
  for (std::size_t i = 0; i < placed.size(); ++i) placed[i].centre_world.pose = poses_world[i];
  return placed;
}

/// The scans' world poses as placed, stamped with their times.
std::vector<StampedPose> scan_poses(const std::vector<PlacedScan>& scans) {
  std::vector<StampedPose> poses;
  for (const PlacedScan& s : scans) poses.push_back({s.scan.t_s, s.centre_world.pose});
  return poses;
}

/// matches.csv's rows: each match with its scans' times and, with pose truth, the true relative
/// pose and the match's NEES in its observed directions.
std::vector<results::MatchRow> match_rows(const ScanSlamEstimate& slam,
                                          const dataset::Truth& truth) {
  std::vector<results::MatchRow> rows;
  rows.reserve(slam.matches.size());
  for (const MatchRecord& m : slam.matches) {
    results::MatchRow row;
    row.t_s = slam.scans[m.scan].scan.t_s;
    row.t_reference_s = slam.scans[m.reference].scan.t_s;
    row.record = m;
    if (!truth.poses.empty()) {
      row.has_truth = true;
      row.truth = interpolate_pose(truth.poses, row.t_reference_s)
                      .between(interpolate_pose(truth.poses, row.t_s));
      row.nees = observed_nees(m.z, m.observed, row.truth);
    }
    rows.push_back(std::move(row));
  }
  return rows;
}

/// The accepted matches between consecutive scans (k, k - 1), for the scale statistic: the
/// spIC translation, and the dead reckoning's (the first thing a consecutive match is measured
/// against).
std::pair<std::vector<MatchTranslation>, std::vector<MatchTranslation>> consecutive_translations(
    const ScanSlamEstimate& slam) {
  std::vector<MatchTranslation> matched, dead_reckoning;
  for (const MatchRecord& m : slam.matches) {
    if (m.rejection != MatchRejection::kNone || m.scan != m.reference + 1) continue;
    MatchTranslation t;
    t.t_reference_s = slam.scans[m.reference].scan.t_s;
    t.t_s = slam.scans[m.scan].scan.t_s;
    t.yaw_reference_rad = slam.online_poses[m.reference].mean.yaw();
    t.translation_reference_m = m.z.mean.translation();
    matched.push_back(t);
    const Pose2 motion = slam.scans[m.reference].centre_world.pose.mean.between(
        slam.scans[m.scan].centre_world.pose.mean);
    t.translation_reference_m = motion.translation();
    dead_reckoning.push_back(t);
  }
  return {matched, dead_reckoning};
}

/// The SLAM's counters for metrics.json (docs/formats.md); sets matches_accepted.
std::vector<std::pair<std::string, double>> slam_diagnostics(
    const ScanSlamEstimate& slam, const std::optional<LinearisationProbe>& linearisation,
    const dataset::Truth& truth, int& matches_accepted) {
  matches_accepted = slam.totals.accepted;
  std::vector<std::pair<std::string, double>> diagnostics = {
      {"scan_candidates", slam.totals.candidates},
      {"scan_matches_valid", slam.totals.matched},
      {"scans_skipped", slam.totals.skipped},
      {"compass_accepted", slam.totals.compass_accepted}};
  const MatchRejectionCounts& counts = slam.totals.rejections;
  for (int reason = 1; reason < kMatchRejectionReasons; ++reason) {
    diagnostics.emplace_back(
        "matches_rejected_" + rejection_name(static_cast<MatchRejection>(reason)),
        counts.rejected[static_cast<std::size_t>(reason)]);
  }
  diagnostics.emplace_back("matches_direction_dropped", counts.direction_dropped);
  if (slam.matches_downweighted) {
    diagnostics.emplace_back("matches_downweighted", *slam.matches_downweighted);
  }
  // How long the consecutive matches make the motion, against the truth (docs/formats.md).
  const auto [matched, dead_reckoning] = consecutive_translations(slam);
  for (const auto& [name, translations] :
       {std::pair{"consecutive_match_scale", &matched},
        std::pair{"consecutive_dead_reckoning_scale", &dead_reckoning}}) {
    if (const std::optional<double> scale =
            match_translation_scale(*translations, truth.positions)) {
      diagnostics.emplace_back(name, *scale);
    }
  }
  // The calibration the back end estimated, with its standard deviation.
  for (const CalibrationEstimate& c : slam.calibration) {
    diagnostics.emplace_back(c.name, c.value);
    diagnostics.emplace_back(c.name + "_sigma", c.sigma);
  }
  // The measured linearisation error (trajectory_slam.linearisation_samples > 0).
  if (linearisation) {
    for (const auto& [name, kind] :
         {std::pair{"linearisation_observation", Linearisation::kObservation},
          std::pair{"linearisation_inversion", Linearisation::kInversion},
          std::pair{"linearisation_pose", Linearisation::kPose}}) {
      if (const std::optional<double> mean = linearisation->tally(kind).mean()) {
        diagnostics.emplace_back(name, *mean);
      }
    }
  }
  return diagnostics;
}

/// What a method estimated, on its clock: dead reckoning (or the integration), or the whole SLAM
/// run when it is a SLAM method; and the scans dead reckoning places after its clock.
struct Estimate {
  DeadReckoningResult dead_reckoning;  ///< the methods without sonar
  std::optional<ScanSlamEstimate> slam;
  /// The study of the filters' linearisations, when the config asks for it
  /// (linearisation_samples > 0) and the method is one of the filters.
  std::optional<LinearisationProbe> linearisation;
  double runtime_s = 0.0;
  std::vector<PlacedScan> dead_reckoning_scans;

  const std::vector<StampedPose>& trajectory() const {
    return slam ? slam->trajectory : dead_reckoning.trajectory;
  }
  /// The scans at the poses the method gives them (a SLAM method: its online estimate).
  std::vector<PlacedScan> scans() const {
    return slam ? placed_at(slam->scans, slam->online_poses) : dead_reckoning_scans;
  }
  bool has_scans() const { return slam || !dead_reckoning_scans.empty(); }
};

Estimate estimate(const Method& method, const dataset::RunInputs& in, SharedInputs* shared) {
  // SLAM methods: the sonar readings are read before the clock starts, like the logs; read once
  // and shared between the methods when `shared` is given.
  std::optional<dataset::SonarInput> own_readings;
  const auto readings = [&]() -> const dataset::SonarInput& {
    std::optional<dataset::SonarInput>& slot = shared ? shared->sonar : own_readings;
    if (!slot) slot = dataset::load_sonar_readings(in);
    return *slot;
  };
  const dataset::SonarInput* sonar =
      method.kind == MethodKind::kTrajectorySlam ? &readings() : nullptr;
  const auto t_begin = std::chrono::steady_clock::now();
  const Eigen::Vector2d p_vehicle_dvl_m(in.calibration.dvl.x_m, in.calibration.dvl.y_m);
  Estimate e;
  if (sonar) {
    const std::unique_ptr<ScanSlam> backend = method.make_slam(in.config, in.start.pose);
    // The study observes the filters' linearisations; other back ends make none it measures.
    if (auto* filter = dynamic_cast<TrajectorySlam*>(backend.get());
        filter && in.config.linearisation_samples > 0) {
      filter->set_linearisation_observer(&e.linearisation.emplace(in.config.linearisation_samples));
    }
    e.slam = run_scan_slam(*backend, in.navigation, sonar->beams, in.config,
                           scan_slam_setup(in, *sonar));
    if (shared && !shared->dead_reckoning_scans && slam_scans_are_dead_reckonings(in.config)) {
      shared->dead_reckoning_scans = e.slam->scans;
    }
  } else if (method.kind == MethodKind::kIntegration) {
    e.dead_reckoning.trajectory = integrate_velocities(in.navigation, in.start);
  } else {
    e.dead_reckoning =
        run_dead_reckoning(in.navigation, in.config.dead_reckoning, p_vehicle_dvl_m, in.start);
  }
  e.runtime_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t_begin).count();
  // Dead reckoning on a dataset with sonar data also places the scans (the map SLAM starts from)
  // and scores their poses like the SLAM's; after the clock, as mapping is not part of the method.
  if (method.kind == MethodKind::kDeadReckoning && dataset::has_sonar_data(in)) {
    if (shared && shared->dead_reckoning_scans) {
      e.dead_reckoning_scans = *shared->dead_reckoning_scans;
    } else {
      e.dead_reckoning_scans = build_placed_scans(in.navigation, readings().beams, in.config,
                                                  scan_slam_setup(in, readings()));
    }
  }
  if (e.trajectory().size() < 2) {
    io::fail_file(in.dataset, "no navigation data after the start time");
  }
  return e;
}

/// The smoothed trajectory scored beside the online one (docs/formats.md).
void add_smoothed_diagnostics(const ScanSlamEstimate& slam, const dataset::Truth& truth,
                              RunMetrics& metrics) {
  const std::optional<ErrorStats> smoothed =
      error_stats(position_errors(*slam.smoothed_trajectory, truth.positions));
  if (smoothed) {
    metrics.diagnostics.emplace_back("smoothed_mean_error_m", smoothed->mean_m);
    metrics.diagnostics.emplace_back("smoothed_final_error_m", smoothed->final_m);
  }
  if (const std::optional<double> anees =
          average_nees(scan_nees(scan_poses(placed_at(slam.scans, slam.final_poses)), truth))) {
    metrics.diagnostics.emplace_back("smoothed_anees", *anees);
  }
}

/// Scores the estimate against the truth (the dataset has one).
void score(const Method& method, const dataset::RunInputs& in, const Estimate& e,
           MethodResult& result) {
  const dataset::Truth& truth = in.truth;
  result.errors = position_errors(e.trajectory(), truth.positions);
  result.metrics = score_errors(truth, result.errors, in.config.segments, in.dataset);
  result.t_first_truth_s = truth.positions.front().t_s;
  RunMetrics& metrics = *result.metrics;
  metrics.method = method.name;
  metrics.runtime_s = e.runtime_s;
  if (e.has_scans()) {
    const std::vector<PlacedScan> scans = e.scans();
    metrics.scans = static_cast<int>(scans.size());
    result.nees = scan_nees(scan_poses(scans), truth);
    metrics.anees = average_nees(result.nees);
  }
  if (e.slam)
    metrics.diagnostics =
        slam_diagnostics(*e.slam, e.linearisation, truth, metrics.matches_accepted);
  if (e.slam && e.slam->smoothed_trajectory) add_smoothed_diagnostics(*e.slam, truth, metrics);
  if (method.kind == MethodKind::kDeadReckoning) {
    const DeadReckoningResult& dr = e.dead_reckoning;
    metrics.diagnostics = {{"dvl_used", dr.dvl_used},
                           {"dvl_rejected", dr.dvl_rejected},
                           {"dvl_without_bottom_lock", in.navigation.dvl_rows_without_bottom_lock},
                           {"dvl_mean_nis", dr.dvl_mean_nis},
                           {"heading_used", dr.heading_used},
                           {"heading_mean_nis", dr.heading_mean_nis}};
  }
}

}  // namespace

/// The library's pipeline settings from a dataset read already.
ScanSlamSetup scan_slam_setup(const dataset::RunInputs& in, const dataset::SonarInput& sonar) {
  ScanSlamSetup setup;
  setup.start = in.start;
  setup.p_vehicle_dvl_m = {in.calibration.dvl.x_m, in.calibration.dvl.y_m};
  setup.p_vehicle_sonar_m = {in.calibration.sonar.x_m, in.calibration.sonar.y_m};
  setup.beams_per_revolution = sonar.beams_per_revolution;
  return setup;
}

MethodResult run_method(const Method& method, const dataset::RunInputs& in, SharedInputs* shared,
                        const ExternalSetup* external) {
  if (method.kind == MethodKind::kExternal) {
    if (external == nullptr) {
      throw io::InputError(method.name + ": an external method needs its setup");
    }
    return run_external_method(method, in, *external);
  }
  const Estimate e = estimate(method, in, shared);
  MethodResult result;
  result.method = method.name;
  result.trajectory = e.trajectory();
  result.depth_m = in.truth.depth_m;
  if (!in.truth.kind.empty()) score(method, in, e, result);
  if (e.has_scans()) result.scans = e.scans();
  if (e.slam) result.matches = match_rows(*e.slam, in.truth);
  if (e.slam) result.smoothed_trajectory = e.slam->smoothed_trajectory;
  if (e.slam) {
    result.calibration_history = e.slam->calibration_history;
    result.estimated_calibration = calibration_with_estimates(in.calibration, e.slam->calibration);
  }
  return result;
}

}  // namespace msislab::app
