#include "app/scans_command.hpp"

#include <CLI/CLI.hpp>
#include <filesystem>
#include <iomanip>
#include <iostream>
#include <memory>

#include "app/cli.hpp"
#include "app/run_method.hpp"
#include "dataset/sonar_readings.hpp"
#include "dataset/truth.hpp"
#include "io/atomic_file.hpp"
#include "io/input_error.hpp"
#include "io/output_guard.hpp"
#include "plot/scan_figures.hpp"
#include "results/results.hpp"
#include "slam/scan_sequence.hpp"

namespace msislab::app {

namespace fs = std::filesystem;

namespace {

/// Mean distance of the scan points from where their readings really were, through the true
/// centre pose: with the compensated point, and with the reading left in its own vehicle frame.
std::pair<double, double> compensation_errors(const std::vector<PlacedScan>& scans,
                                              const std::vector<StampedPose>& truth) {
  double compensated = 0.0, uncompensated = 0.0;
  std::size_t n = 0;
  for (const PlacedScan& placed : scans) {
    const Pose2 centre = interpolate_pose(truth, placed.scan.t_s);
    for (const ScanPoint& point : placed.scan.points) {
      const Eigen::Vector2d real = interpolate_pose(truth, point.t_s).transform(point.p_vehicle_m);
      compensated += (centre.transform(point.p_m) - real).norm();
      uncompensated += (centre.transform(point.p_vehicle_m) - real).norm();
      ++n;
    }
  }
  if (n == 0) return {0.0, 0.0};
  return {compensated / static_cast<double>(n), uncompensated / static_cast<double>(n)};
}

void write_outputs(const fs::path& out, const std::vector<PlacedScan>& scans,
                   const std::vector<Eigen::Vector2d>& truth_track, const std::string& truth_kind,
                   int figure_scan) {
  results::write_scans_csv((out / "scans.csv").string(), scans);
  const std::vector<Eigen::Vector2d> points = world_points(scans);
  std::vector<Eigen::Vector2d> centres;
  for (const PlacedScan& s : scans) centres.push_back(s.centre_world.pose.mean.translation());
  results::write_points_ply((out / "map.ply").string(), points);
  std::vector<plot::Track> tracks;
  if (!truth_track.empty()) tracks.push_back({truth_kind + " truth", truth_track, 0x00a000});
  tracks.push_back({"dead reckoning", centres, 0x0000ff});
  plot::write_map_png(
      (out / "map.png").string(),
      "Scan points placed by dead reckoning (" + std::to_string(scans.size()) + " scans)", points,
      tracks);
  const std::size_t k = figure_scan >= 0 && static_cast<std::size_t>(figure_scan) < scans.size()
                            ? static_cast<std::size_t>(figure_scan)
                            : scans.size() / 2;
  std::vector<Eigen::Vector2d> before, after;
  for (const ScanPoint& p : scans[k].scan.points) {
    before.push_back(p.p_vehicle_m);
    after.push_back(p.p_m);
  }
  plot::write_scan_comparison_png(
      (out / "compensation.png").string(),
      "scan " + std::to_string(k) + " at t = " + std::to_string(scans[k].scan.t_s) + " s", before,
      after);
}

}  // namespace

namespace {
io::OutputRequest scans_output(const ScansOptions& options) {
  return {
      options.out_dir, "scans", "scans", {options.dataset_dir, options.config_path}, options.force};
}
}  // namespace

ScansSummary build_scans_command(const ScansOptions& options) {
  io::check_output_folder(scans_output(options));
  const dataset::RunInputs in = dataset::load_run_inputs(options.dataset_dir, options.config_path);
  if (!in.noise_note.empty()) std::cerr << "msislab: " << in.noise_note << '\n';
  const SlamConfig& config = in.config;
  const Calibration& calibration = in.calibration;
  const dataset::Truth& truth = in.truth;
  const dataset::SonarInput sonar =
      dataset::load_sonar_readings(in.files, calibration, config.segmentation);

  const std::vector<PlacedScan> scans =
      build_placed_scans(in.navigation, sonar.beams, config, scan_slam_setup(in, sonar));
  if (scans.empty()) {
    io::fail_file(options.dataset_dir, "no complete sonar revolution after the navigation start");
  }

  ScansSummary summary;
  summary.source = sonar.source;
  summary.beams = sonar.beams.size();
  for (const BeamReadings& b : sonar.beams) summary.beams_with_readings += !b.readings.empty();
  summary.scans = scans.size();
  for (const PlacedScan& s : scans) summary.points += s.scan.points.size();
  if (!truth.poses.empty()) {
    const auto [with, without] = compensation_errors(scans, truth.poses);
    summary.compensated_error_m = with;
    summary.uncompensated_error_m = without;
  }

  io::StagedFolder staged(scans_output(options));
  std::vector<Eigen::Vector2d> truth_track;
  for (const PositionFix& f : truth.positions) truth_track.push_back(f.p_world_m);
  write_outputs(staged.path(), scans, truth_track, truth.kind, options.figure_scan);
  staged.commit();
  return summary;
}

void add_scans_command(CLI::App& app, CommandLine&) {
  auto options = std::make_shared<ScansOptions>();
  CLI::App* scans = app.add_subcommand(
      "scans",
      "Segment the sonar beams and build motion-compensated scans placed by dead "
      "reckoning; writes scans.csv, map.ply, map.png and compensation.png");
  scans->add_option("DATASET_DIR", options->dataset_dir, "Dataset directory, real or synthetic")
      ->required();
  scans->add_option("--out,-o", options->out_dir, "Output directory")->required();
  scans->add_option("--config,-c", options->config_path,
                    "SLAM config YAML (segmentation and dead_reckoning sections)");
  scans->add_option("--figure-scan", options->figure_scan,
                    "Scan drawn before/after compensation (default: the middle one)");
  add_force_flag(*scans, options->force);
  scans->callback([options] {
    const ScansSummary s = build_scans_command(*options);
    std::cout << "wrote " << options->out_dir << ": " << s.scans << " scans, " << s.points
              << " points from " << s.beams_with_readings << " of " << s.beams << " beams ("
              << s.source << ")";
    if (s.compensated_error_m) {
      std::cout << std::fixed << std::setprecision(3)
                << "; reading placement error against the truth: " << *s.compensated_error_m
                << " m compensated, " << *s.uncompensated_error_m << " m uncompensated";
    }
    std::cout << std::endl;
  });
}

}  // namespace msislab::app
