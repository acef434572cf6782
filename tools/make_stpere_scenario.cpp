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
#include <iomanip>
#include <iostream>
#include <limits>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include "eval/evaluation.hpp"
#include "io/atomic_file.hpp"
#include "io/dataset.hpp"
#include "io/mesh_io.hpp"
#include "sim/vehicle.hpp"

namespace {

using Path = std::vector<Eigen::Vector2d>;

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
};

/// The scene's walls as 2-D segments and its bottom as 2-D triangles (from the OBJ groups).
struct SceneOutline {
  std::vector<std::pair<Eigen::Vector2d, Eigen::Vector2d>> walls;
  std::vector<std::array<Eigen::Vector2d, 3>> bottom;
};

SceneOutline load_outline(const std::string& path) {
  const msislab::sim::TriangleMesh mesh = msislab::io::read_mesh(path, {});
  SceneOutline outline;
  for (std::size_t i = 0; i < mesh.triangles.size(); ++i) {
    const std::string& group = mesh.group_names[mesh.material_ids[i]];
    std::array<Eigen::Vector2d, 3> corners;
    for (int k = 0; k < 3; ++k) {
      corners[k] = mesh.vertices_m[mesh.triangles[i][k]].head<2>().cast<double>();
    }
    if (group == "bottom") outline.bottom.push_back(corners);
    if (group != "walls") continue;
    for (int k = 0; k < 3; ++k) {
      const Eigen::Vector2d& a = corners[k];
      const Eigen::Vector2d& b = corners[(k + 1) % 3];
      if ((b - a).norm() > 1e-6) outline.walls.emplace_back(a, b);
    }
  }
  if (outline.walls.empty() || outline.bottom.empty()) {
    throw std::runtime_error(path + ": needs the groups 'walls' and 'bottom'");
  }
  return outline;
}

bool inside(const SceneOutline& outline, const Eigen::Vector2d& p) {
  const auto cross = [](const Eigen::Vector2d& u, const Eigen::Vector2d& v) {
    return u.x() * v.y() - u.y() * v.x();
  };
  for (const auto& [a, b, c] : outline.bottom) {
    const double s1 = cross(b - a, p - a), s2 = cross(c - b, p - b), s3 = cross(a - c, p - c);
    if ((s1 >= 0 && s2 >= 0 && s3 >= 0) || (s1 <= 0 && s2 <= 0 && s3 <= 0)) return true;
  }
  return false;
}

/// The wall point nearest to p.
Eigen::Vector2d nearest_wall_point(const SceneOutline& outline, const Eigen::Vector2d& p) {
  Eigen::Vector2d nearest = outline.walls.front().first;
  for (const auto& [a, b] : outline.walls) {
    const double u = std::clamp((p - a).dot(b - a) / (b - a).squaredNorm(), 0.0, 1.0);
    const Eigen::Vector2d q = a + u * (b - a);
    if ((q - p).squaredNorm() < (nearest - p).squaredNorm()) nearest = q;
  }
  return nearest;
}

/// Signed clearance: distance to the nearest wall, negative outside the scene.
double clearance_m(const SceneOutline& outline, const Eigen::Vector2d& p) {
  const double distance_m = (nearest_wall_point(outline, p) - p).norm();
  return inside(outline, p) ? distance_m : -distance_m;
}

/// Centred moving average over window_s; the window shrinks symmetrically at the ends, so the
/// first and last fixes stay where they are.
Path smooth_track(const std::vector<msislab::PositionFix>& fixes, double window_s) {
  Path smoothed;
  std::size_t lo = 0, hi = 0;
  for (const msislab::PositionFix& fix : fixes) {
    const double half_s =
        std::min({window_s / 2.0, fix.t_s - fixes.front().t_s, fixes.back().t_s - fix.t_s});
    while (fixes[lo].t_s < fix.t_s - half_s) ++lo;
    while (hi + 1 < fixes.size() && fixes[hi + 1].t_s <= fix.t_s + half_s) ++hi;
    Eigen::Vector2d sum = Eigen::Vector2d::Zero();
    for (std::size_t i = lo; i <= hi; ++i) sum += fixes[i].p_world_m;
    smoothed.push_back(sum / static_cast<double>(hi - lo + 1));
  }
  return smoothed;
}

/// Douglas-Peucker (Douglas and Peucker 1973) on an open polyline: the indices of the points kept.
std::vector<std::size_t> simplify(const Path& path, double tolerance_m) {
  std::vector<bool> keep(path.size(), false);
  keep.front() = keep.back() = true;
  std::vector<std::pair<std::size_t, std::size_t>> spans = {{0, path.size() - 1}};
  while (!spans.empty()) {
    const auto [first, last] = spans.back();
    spans.pop_back();
    const Eigen::Vector2d a = path[first], ab = path[last] - a;
    double farthest_m = 0.0;
    std::size_t farthest = first;
    for (std::size_t i = first + 1; i < last; ++i) {
      const double u = ab.squaredNorm() > 0.0
                           ? std::clamp((path[i] - a).dot(ab) / ab.squaredNorm(), 0.0, 1.0)
                           : 0.0;
      const double distance_m = (path[i] - a - u * ab).norm();
      if (distance_m > farthest_m) {
        farthest_m = distance_m;
        farthest = i;
      }
    }
    if (farthest_m <= tolerance_m) continue;
    keep[farthest] = true;
    spans.emplace_back(first, farthest);
    spans.emplace_back(farthest, last);
  }
  std::vector<std::size_t> kept;
  for (std::size_t i = 0; i < path.size(); ++i) {
    if (keep[i]) kept.push_back(i);
  }
  return kept;
}

/// Moves a waypoint away from (or back inside) the nearest wall until it has the clearance.
/// Returns the distance moved.
double pull_inside(const SceneOutline& outline, Eigen::Vector2d& p, double wanted_m) {
  const Eigen::Vector2d start = p;
  for (int iteration = 0; iteration < 20 && clearance_m(outline, p) < wanted_m; ++iteration) {
    const Eigen::Vector2d q = nearest_wall_point(outline, p);
    const Eigen::Vector2d inward = (inside(outline, p) ? p - q : q - p).normalized();
    p = q + inward * (wanted_m + 0.05);
  }
  return (p - start).norm();
}

double length_m(const Path& path) {
  double total_m = 0.0;
  for (std::size_t i = 1; i < path.size(); ++i) total_m += (path[i] - path[i - 1]).norm();
  return total_m;
}

/// Smallest signed clearance along the legs, sampled every 0.25 m.
double min_leg_clearance_m(const SceneOutline& outline, const Path& path) {
  double lowest_m = std::numeric_limits<double>::infinity();
  for (std::size_t i = 1; i < path.size(); ++i) {
    const int samples = 1 + static_cast<int>((path[i] - path[i - 1]).norm() / 0.25);
    for (int k = 0; k <= samples; ++k) {
      const Eigen::Vector2d p = path[i - 1] + (path[i] - path[i - 1]) * k / samples;
      lowest_m = std::min(lowest_m, clearance_m(outline, p));
    }
  }
  return lowest_m;
}

/// The time (from the start) at which the vehicle passes each waypoint: its closest approach,
/// searched in order along the trajectory.
std::vector<double> arrival_times_s(const msislab::sim::VehicleTrajectory& truth,
                                    const Path& path) {
  const auto& samples = truth.samples();
  std::vector<double> arrivals = {0.0};
  std::size_t i = 0;
  for (std::size_t k = 1; k < path.size(); ++k) {
    double best_m = std::numeric_limits<double>::infinity();
    std::size_t best = i;
    for (; i < samples.size(); ++i) {
      const double d_m = (samples[i].pose.translation() - path[k]).norm();
      if (d_m < best_m) best_m = d_m, best = i;
      if (best_m < 3.0 && d_m > best_m + 2.0) break;
    }
    i = best;
    arrivals.push_back(samples[best].t_s - truth.start_s());
  }
  return arrivals;
}

/// Leg speeds that make the simulated vehicle reach every waypoint when the real one did: first
/// leg length / real leg time, then each scaled by its simulated / real duration (the pursuit
/// cuts corners) a few times. Returns the speeds and the arrival times reached.
std::pair<std::vector<double>, std::vector<double>> timed_leg_speeds(
    const Path& path, const std::vector<double>& real_times_s, const Options& options) {
  msislab::sim::VehicleConfig vehicle;
  vehicle.path_m = path;
  for (std::size_t k = 1; k < path.size(); ++k) {
    const double leg_s = std::max(real_times_s[k] - real_times_s[k - 1], 1.0);
    vehicle.leg_speeds_mps.push_back(std::clamp((path[k] - path[k - 1]).norm() / leg_s, 0.02, 1.0));
  }
  std::vector<double> arrivals;
  for (int iteration = 0; iteration <= options.timing_iterations; ++iteration) {
    arrivals = arrival_times_s(msislab::sim::follow_path(vehicle), path);
    if (iteration == options.timing_iterations) break;
    for (std::size_t k = 1; k < path.size(); ++k) {
      const double simulated_s = std::max(arrivals[k] - arrivals[k - 1], 1.0);
      const double real_s = std::max(real_times_s[k] - real_times_s[k - 1], 1.0);
      vehicle.leg_speeds_mps[k - 1] =
          std::clamp(vehicle.leg_speeds_mps[k - 1] * simulated_s / real_s, 0.02, 1.0);
    }
  }
  return {vehicle.leg_speeds_mps, arrivals};
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

std::string scenario_yaml(const Options& options, const Path& path,
                          const std::vector<double>& leg_speeds_mps, const std::string& mesh_ref) {
  std::ostringstream yaml;
  yaml << "# The St. Pere replica: the real GPS track in the local frame (x East, y North, m from "
          "the\n# first fix), smoothed over "
       << options.smooth_s << " s, simplified at " << options.tolerance_m
       << " m, waypoints kept >= " << options.clearance_m
       << " m off the walls.\n# Each leg's speed makes the vehicle reach its waypoints when the "
          "real "
          "one did, so the\n# segments are the real times. Written by msislab_make_stpere_scenario "
          "(docs/scenes.md).\n";
  // Materials: rough quay walls and moored objects with little specular reflection, a mud
  // bottom about 22 dB below them (docs/simulator.md, "Calibration against St. Pere").
  yaml << "name: stpere_replica\nseed: 42\nscene:\n  mesh: " << mesh_ref
       << "\n  groups:\n    walls: {backscatter: 0.5, specular: 0.05}\n"
          "    clutter: {backscatter: 0.5, specular: 0.05}\n"
          "    bottom: {backscatter: 0.003, specular: 0.3}\nvehicle:\n  depth_m: "
       << options.depth_m << "\n  speed_mps: 0.2\n  path:\n"
       << std::fixed << std::setprecision(2);
  for (const Eigen::Vector2d& p : path) yaml << "    - [" << p.x() << ", " << p.y() << "]\n";
  yaml << "  leg_speeds_mps:\n" << std::setprecision(4);
  for (const double v : leg_speeds_mps) yaml << "    - " << v << "\n";
  yaml << std::setprecision(0) << "segments: {loop: [0, " << options.leave_basin_s << "], canal: ["
       << options.leave_basin_s << ", " << options.segments_end_s << "], exit: [" << options.exit_s
       << ", " << options.segments_end_s << "]}\n"
       << "sonar: {}\ndvl: {}\nmru: {}\ngps: {}\n";
  return yaml.str();
}

void make_scenario(const Options& options) {
  const msislab::io::DatasetFiles files = msislab::io::find_dataset_files(options.dataset_dir);
  const std::vector<msislab::PositionFix> fixes =
      msislab::io::load_gps_fixes(files, msislab::io::load_calibration(files));
  const SceneOutline outline = load_outline(options.scene_path);
  const Path smoothed = smooth_track(fixes, options.smooth_s);
  const Waypoints waypoints = place_waypoints(fixes, smoothed, outline, options);
  const Path& path = waypoints.path;
  const auto [leg_speeds_mps, arrivals_s] = timed_leg_speeds(path, waypoints.real_times_s, options);

  double lowest_m = std::numeric_limits<double>::infinity();
  for (const Eigen::Vector2d& p : path) lowest_m = std::min(lowest_m, clearance_m(outline, p));
  double worst_s = 0.0;
  for (std::size_t k = 0; k < path.size(); ++k) {
    worst_s = std::max(worst_s, std::abs(arrivals_s[k] - waypoints.real_times_s[k]));
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

  std::string mesh_ref = options.scene_path;
  if (!options.out_path.empty()) {
    const auto out_dir = std::filesystem::absolute(options.out_path).parent_path();
    mesh_ref = std::filesystem::relative(std::filesystem::absolute(options.scene_path), out_dir);
  }
  const std::string yaml = scenario_yaml(options, path, leg_speeds_mps, mesh_ref);
  if (options.out_path.empty()) {
    std::cout << yaml;
    return;
  }
  msislab::io::write_file_atomically(options.out_path, [&](std::ostream& out) { out << yaml; });
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
