// msislab_make_stpere_scenario: writes the St. Pere replica scenario (docs/scenes.md): the real GPS
// track, smoothed (centred moving average) and simplified (Douglas-Peucker) into waypoints in the
// local frame, each kept inside the marina scene with a small clearance from its walls; each leg's
// speed makes the simulated vehicle reach its waypoints when the real one did.
#include <CLI/CLI.hpp>
#include <Eigen/Core>
#include <algorithm>
#include <array>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <iostream>
#include <limits>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include "dataset/dataset.hpp"
#include "eval/evaluation.hpp"
#include "io/atomic_file.hpp"
#include "io/heading_csv.hpp"
#include "io/input_error.hpp"
#include "io/mesh_io.hpp"
#include "io/output_guard.hpp"
#include "io/stpere_logs.hpp"
#include "sim/scenario_path.hpp"

namespace {

using msislab::sim::clearance_m;
using msislab::sim::length_m;
using msislab::sim::min_leg_clearance_m;
using msislab::sim::Path2;
using msislab::sim::pull_inside;
using msislab::sim::SceneOutline;
using msislab::sim::simplify;
using Path = Path2;

struct Options {
  std::string dataset_dir;
  std::string scene_path = "scenes/stpere_marina.obj";
  std::string out_path;            ///< empty: standard output
  double smooth_s = 20.0;          ///< moving-average window, s
  double tolerance_m = 1.5;        ///< Douglas-Peucker tolerance, m
  double clearance_m = 0.75;       ///< wanted distance from every waypoint to the walls, m
  double depth_m = 1.5;            ///< vehicle depth, m
  double leave_basin_s = 2000.0;   ///< real time (from the first fix) the basin is left, s
  double exit_s = 2900.0;          ///< real time the exit part (canal end, east opening) begins, s
  double segments_end_s = 3400.0;  ///< end of the last segment, s
  int timing_iterations = 8;       ///< leg speed corrections against the simulated vehicle
  std::string heading_out;  ///< also write the real heading history here (vehicle.heading_csv)
};

/// The outline of the scene file (its groups 'walls' and 'bottom').
SceneOutline load_outline(const std::string& path) {
  try {
    return msislab::sim::outline_of(msislab::io::read_mesh(path, {}));
  } catch (const std::invalid_argument& e) {
    throw std::runtime_error(path + ": " + e.what());
  }
}

/// The GPS track smoothed over window_s.
Path smooth_track(const std::vector<msislab::PositionFix>& fixes, double window_s) {
  std::vector<double> t_s;
  Path p_m;
  for (const msislab::PositionFix& fix : fixes) {
    t_s.push_back(fix.t_s);
    p_m.push_back(fix.p_world_m);
  }
  return msislab::sim::smooth_track(t_s, p_m, window_s);
}

/// Waypoints with the real time (from the first fix) of the fix each was kept from.
struct Waypoints {
  Path path;
  std::vector<double> real_times_s;
};

/// The track smoothed and simplified; every waypoint then pulled inside the scene with the wanted
/// clearance where it has less (reported on stderr), and one closer than 0.1 m to the previous
/// dropped.
Waypoints place_waypoints(const std::vector<msislab::PositionFix>& fixes, const Path& smoothed,
                          const SceneOutline& outline, const Options& options) {
  Waypoints waypoints;
  for (const std::size_t i : simplify(smoothed, options.tolerance_m)) {
    Eigen::Vector2d p = smoothed[i];
    const double before_m = clearance_m(outline, p);
    if (const double moved_m = pull_inside(outline, p, options.clearance_m); moved_m > 0.0) {
      std::cerr << std::fixed << std::setprecision(1) << "waypoint (" << smoothed[i].x() << ", "
                << smoothed[i].y() << ") had clearance " << before_m << " m: moved "
                << std::setprecision(2) << moved_m << " m to (" << p.x() << ", " << p.y() << ")\n";
    }
    if (!waypoints.path.empty() && (p - waypoints.path.back()).norm() < 0.1) continue;
    waypoints.path.push_back(p);
    waypoints.real_times_s.push_back(fixes[i].t_s - fixes.front().t_s);
  }
  return waypoints;
}

// The St. Pere MiniKing as its detections show it (docs/simulator.md, "Echo shape"): a 500 us
// box pulse with no receiver tail, a 6 deg (two-way -3 dB) horizontal beam traced over 2.5
// beamwidths either side, and the publisher's detector with a 23-bin window. The sonar logs until
// the real one stopped, stop_s after the first fix.
std::string stpere_sonar_yaml(double stop_s) {
  std::ostringstream yaml;
  yaml << std::fixed << std::setprecision(1) << "sonar:\n  stop_s: " << stop_s
       << "\n  pulse_length_us: 500\n  receiver_time_constant_us: 0\n"
          "  horizontal_beamwidth_deg: 6\n  horizontal_span_beamwidths: 2.5\n"
          "  rays_horizontal: 24\ndetections: {smoothing_bins: 23}\n";
  return yaml.str();
}

std::string scenario_yaml(const Options& options, const Path& path,
                          const std::vector<double>& leg_speeds_mps, const std::string& mesh_ref,
                          double sonar_stop_s, const std::string& heading_ref) {
  std::ostringstream yaml;
  yaml << "# The St. Pere replica: the real GPS track in the local frame (x East, y North, m from "
          "the\n# first fix), smoothed over "
       << options.smooth_s << " s, simplified at " << options.tolerance_m
       << " m, waypoints kept >= " << options.clearance_m
       << " m off the walls.\n# Each leg's speed makes the vehicle reach its waypoints when the "
          "real "
          "one did, so the\n# segments are the real times. Written by msislab_make_stpere_scenario "
          "(docs/scenes.md).\n";
  if (!heading_ref.empty()) {
    yaml << "# The vehicle points where the real one did (the MTi heading at 1 Hz, " << heading_ref
         << ").\n";
  }
  // Materials: rough quay walls and moored objects with little specular reflection whose
  // backscatter falls as cos(incidence), a mud bottom about 22 dB below them (docs/simulator.md,
  // "Calibration against St. Pere").
  yaml << "name: stpere_replica\nseed: 42\nscene:\n  mesh: " << mesh_ref
       << "\n  groups:\n    walls: {backscatter: 0.5, specular: 0.05, incidence_exponent: 1}\n"
          "    clutter: {backscatter: 0.5, specular: 0.05, incidence_exponent: 1}\n"
          "    bottom: {backscatter: 0.003, specular: 0.3}\nvehicle:\n  depth_m: "
       << options.depth_m << "\n  speed_mps: 0.2\n  path:\n"
       << std::fixed << std::setprecision(2);
  for (const Eigen::Vector2d& p : path) yaml << "    - [" << p.x() << ", " << p.y() << "]\n";
  if (!heading_ref.empty()) yaml << "  heading_csv: " << heading_ref << "\n";
  yaml << "  leg_speeds_mps:\n" << std::setprecision(4);
  for (const double v : leg_speeds_mps) yaml << "    - " << v << "\n";
  yaml << std::setprecision(0) << "segments: {loop: [0, " << options.leave_basin_s << "], canal: ["
       << options.leave_basin_s << ", " << options.segments_end_s << "], exit: [" << options.exit_s
       << ", " << options.segments_end_s << "]}\n"
       << stpere_sonar_yaml(sonar_stop_s) << "dvl: {}\nmru: {}\ngps: {}\n";
  return yaml.str();
}

constexpr const char* kTool = "msislab_make_stpere_scenario";

/// True for a scenario this tool wrote: its opening comment says so.
bool written_by_this_tool(const std::string& path) {
  std::ifstream in(path);
  std::string line;
  for (int i = 0; i < 8 && std::getline(in, line); ++i) {
    if (line.find(std::string("Written by ") + kTool) != std::string::npos) return true;
  }
  return false;
}

/// True when `heading` is the heading history that this tool's earlier scenario at `scenario`
/// names (so the tool wrote it too and may replace it).
bool named_by_earlier_scenario(const std::string& scenario, const std::string& heading) {
  namespace fs = std::filesystem;
  if (scenario.empty() || !written_by_this_tool(scenario)) return false;
  std::ifstream in(scenario);
  const std::string key = "  heading_csv: ";
  for (std::string line; std::getline(in, line);) {
    if (line.rfind(key, 0) != 0) continue;
    std::error_code ec;
    return fs::equivalent(fs::path(scenario).parent_path() / line.substr(key.size()), heading, ec);
  }
  return false;
}

/// Refuses, before anything is computed, an output path that holds what the tool did not write
/// (io/output_guard: exit status 2 naming the path).
void check_outputs(const Options& options) {
  const std::vector<std::string> inputs = {options.dataset_dir, options.scene_path};
  if (!options.out_path.empty()) {
    msislab::io::check_output_file({options.out_path, "scenario", kTool, inputs, false},
                                   written_by_this_tool);
  }
  if (options.heading_out.empty()) return;
  namespace fs = std::filesystem;
  if (!options.out_path.empty() && fs::absolute(options.heading_out).lexically_normal() ==
                                       fs::absolute(options.out_path).lexically_normal()) {
    msislab::io::fail_file(options.heading_out,
                           "is also --out; give the heading history its own name");
  }
  const bool ours = named_by_earlier_scenario(options.out_path, options.heading_out);
  msislab::io::check_output_file(
      {options.heading_out, "heading history", kTool, inputs, false},
      ours ? +[](const std::string&) { return true; } : +[](const std::string&) { return false; });
}

/// Prints how the waypoints fit the real track: length, timing, speeds and wall clearance.
void print_path_summary(const std::vector<msislab::PositionFix>& fixes, const Path& smoothed,
                        const SceneOutline& outline, const Path& path,
                        const std::vector<double>& real_times_s,
                        const std::vector<double>& leg_speeds_mps,
                        const std::vector<double>& arrivals_s) {
  double lowest_m = std::numeric_limits<double>::infinity();
  for (const Eigen::Vector2d& p : path) lowest_m = std::min(lowest_m, clearance_m(outline, p));
  double worst_s = 0.0;
  for (std::size_t k = 0; k < path.size(); ++k) {
    worst_s = std::max(worst_s, std::abs(arrivals_s[k] - real_times_s[k]));
  }
  const auto [slowest, fastest] = std::minmax_element(leg_speeds_mps.begin(), leg_speeds_mps.end());
  std::cerr << std::fixed << std::setprecision(1) << path.size() << " waypoints, path "
            << length_m(path) << " m (smoothed GPS track " << length_m(smoothed) << " m), run "
            << fixes.back().t_s - fixes.front().t_s << " s; simulated arrival at the last waypoint "
            << arrivals_s.back() << " s\n"
            << std::setprecision(3) << "leg speeds " << *slowest << " .. " << *fastest << " m/s\n"
            << std::setprecision(1) << "timing: every waypoint reached within " << worst_s
            << " s of the real vehicle\n"
            << std::setprecision(2) << "clearance from the walls: waypoints >= " << lowest_m
            << " m, legs >= " << min_leg_clearance_m(outline, path) << " m\n";
}

/// Writes --heading-out (when given) and returns its path relative to the scenario's folder;
/// empty without it.
std::string write_heading_history(const Options& options,
                                  const msislab::dataset::DatasetFiles& files,
                                  const msislab::Calibration& calibration,
                                  const std::vector<msislab::PositionFix>& fixes) {
  if (options.heading_out.empty()) return "";
  // The real MTi heading (scene frame, through the calibration) at 1 Hz from the first fix,
  // to the MTi log's own resolution (1 ms, 0.001 deg).
  const auto thousandths = [](double x) { return std::round(x * 1000.0) / 1000.0; };
  std::vector<Eigen::Vector2d> heading;
  for (const msislab::HeadingReading& h :
       msislab::dataset::load_navigation(files, calibration).heading) {
    const double t_s = h.t_s - fixes.front().t_s;
    if (t_s < 0.0 || t_s > fixes.back().t_s - fixes.front().t_s + 1.0) continue;
    if (heading.empty() || t_s >= heading.back().x() + 1.0) {
      heading.emplace_back(t_s, h.yaw_rad * 180.0 / M_PI);
    }
  }
  for (Eigen::Vector2d& row : heading) row = row.unaryExpr(thousandths);
  msislab::io::write_heading_csv(options.heading_out, heading);
  std::cerr << "wrote " << options.heading_out << " (" << heading.size() << " headings)\n";
  const auto out_dir =
      std::filesystem::absolute(options.out_path.empty() ? "." : options.out_path).parent_path();
  return std::filesystem::relative(std::filesystem::absolute(options.heading_out), out_dir)
      .string();
}

void make_scenario(const Options& options) {
  check_outputs(options);
  const msislab::dataset::DatasetFiles files =
      msislab::dataset::find_dataset_files(options.dataset_dir);
  const msislab::Calibration calibration = msislab::dataset::load_calibration(files);
  const std::vector<msislab::PositionFix> fixes =
      msislab::dataset::load_gps_fixes(files, calibration);
  if (!files.beam_times) throw std::runtime_error(options.dataset_dir + ": no *_IS_timestamps.log");
  // The last beam on the navigation clock (docs/simulator.md, "Sonar clock offset").
  const double sonar_stop_s = msislab::io::read_beam_times_log(*files.beam_times).back().t_log_s +
                              calibration.sonar.time_offset_s - fixes.front().t_s;
  const SceneOutline outline = load_outline(options.scene_path);
  const Path smoothed = smooth_track(fixes, options.smooth_s);
  const Waypoints waypoints = place_waypoints(fixes, smoothed, outline, options);
  const Path& path = waypoints.path;
  const auto [leg_speeds_mps, arrivals_s] =
      msislab::sim::timed_leg_speeds(path, waypoints.real_times_s, options.timing_iterations);

  print_path_summary(fixes, smoothed, outline, path, waypoints.real_times_s, leg_speeds_mps,
                     arrivals_s);

  std::string mesh_ref = options.scene_path;
  if (!options.out_path.empty()) {
    const auto out_dir = std::filesystem::absolute(options.out_path).parent_path();
    mesh_ref = std::filesystem::relative(std::filesystem::absolute(options.scene_path), out_dir);
  }
  const std::string heading_ref = write_heading_history(options, files, calibration, fixes);
  const std::string yaml =
      scenario_yaml(options, path, leg_speeds_mps, mesh_ref, sonar_stop_s, heading_ref);
  if (options.out_path.empty()) {
    std::cout << yaml;
    return;
  }
  msislab::io::write_text_atomically(options.out_path, yaml);
  std::cerr << "wrote " << options.out_path << "\n";
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"Write the St. Pere replica scenario from the real GPS track (YAML)"};
  Options options;
  app.add_option("--dataset", options.dataset_dir, "St. Pere dataset directory")->required();
  app.add_option("--scene", options.scene_path, "Marina scene (OBJ with walls and bottom)")
      ->capture_default_str();
  app.add_option("--out", options.out_path, "Output YAML (standard output when absent)");
  app.add_option("--smooth", options.smooth_s, "Moving-average window, s")
      ->check(CLI::PositiveNumber)
      ->capture_default_str();
  app.add_option("--tolerance", options.tolerance_m, "Simplification tolerance, m")
      ->check(CLI::PositiveNumber)
      ->capture_default_str();
  app.add_option("--heading-out", options.heading_out,
                 "Also write the real heading history (CSV) and point the scenario at it");
  app.add_option("--clearance", options.clearance_m, "Waypoint clearance from the walls, m")
      ->check(CLI::NonNegativeNumber)
      ->capture_default_str();
  CLI11_PARSE(app, argc, argv);
  try {
    make_scenario(options);
  } catch (const std::exception& e) {
    std::cerr << "msislab_make_stpere_scenario: " << e.what() << "\n";
    return 2;
  }
  return 0;
}
