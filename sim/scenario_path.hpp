// The geometry of the scenario generators (tools/make_stpere_scenario): a scene's outline in the
// plane (its walls and the bottom they enclose), clearance from the walls, a GPS track smoothed
// and simplified into waypoints kept inside the scene, and leg speeds that make the simulated
// vehicle reach each waypoint when the real one did.
#pragma once

#include <Eigen/Core>
#include <array>
#include <cstddef>
#include <utility>
#include <vector>

#include "sim/mesh.hpp"
#include "sim/vehicle.hpp"

namespace msislab::sim {

using Path2 = std::vector<Eigen::Vector2d>;

/// A scene's walls as 2-D segments and its bottom as 2-D triangles.
struct SceneOutline {
  std::vector<std::pair<Eigen::Vector2d, Eigen::Vector2d>> walls;
  std::vector<std::array<Eigen::Vector2d, 3>> bottom;
};

/// The outline of a mesh from its groups 'walls' and 'bottom'; std::invalid_argument when either
/// is missing.
SceneOutline outline_of(const TriangleMesh& mesh);

/// p lies on the bottom (inside the scene).
bool inside(const SceneOutline& outline, const Eigen::Vector2d& p);
/// The wall point nearest to p.
Eigen::Vector2d nearest_wall_point(const SceneOutline& outline, const Eigen::Vector2d& p);
/// Signed clearance: distance to the nearest wall, negative outside the scene.
double clearance_m(const SceneOutline& outline, const Eigen::Vector2d& p);
/// Moves a waypoint away from (or back inside) the nearest wall until it has the clearance
/// `wanted_m` (at most 20 steps). Returns the distance moved.
double pull_inside(const SceneOutline& outline, Eigen::Vector2d& p, double wanted_m);
/// Smallest signed clearance along the legs, sampled every 0.25 m.
double min_leg_clearance_m(const SceneOutline& outline, const Path2& path);
/// Whether the path, sampled every 0.25 m along its legs, enters a convex polygon given
/// counter-clockwise (its boundary counts as inside).
bool path_enters(const Path2& path, const Path2& ccw_convex_polygon);

/// Centred moving average over window_s of positions at times t_s (increasing); the window
/// shrinks symmetrically at the ends, so the first and last positions stay where they are.
Path2 smooth_track(const std::vector<double>& t_s, const Path2& p_m, double window_s);
/// Douglas-Peucker (Douglas and Peucker 1973) on an open polyline: the indices of the points kept,
/// the first and last always.
std::vector<std::size_t> simplify(const Path2& path, double tolerance_m);
/// The polyline's length.
double length_m(const Path2& path);

/// The time (from the start) at which the vehicle passes each waypoint: its closest approach,
/// searched in order along the trajectory (0 for the first).
std::vector<double> arrival_times_s(const VehicleTrajectory& truth, const Path2& path);

/// Leg speeds that make the simulated vehicle (follow_path) reach every waypoint when the real
/// one did (real_times_s, from the start): first leg length / real leg time, then each scaled by
/// its simulated / real duration (the pursuit cuts corners) `iterations` times; speeds within
/// [0.02, 1] m/s. Returns the speeds and the arrival times reached.
std::pair<std::vector<double>, std::vector<double>> timed_leg_speeds(
    const Path2& path, const std::vector<double>& real_times_s, int iterations);

}  // namespace msislab::sim
