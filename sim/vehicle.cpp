#include "sim/vehicle.hpp"

#include <algorithm>
#include <cassert>
#include <cmath>
#include <stdexcept>

namespace msislab::sim {

VehicleTrajectory::VehicleTrajectory(std::vector<VehicleState> samples)
    : samples_(std::move(samples)) {
  assert(!samples_.empty());
}

VehicleState VehicleTrajectory::at(double t_s) const {
  if (t_s <= samples_.front().t_s) return samples_.front();
  if (t_s >= samples_.back().t_s) return samples_.back();
  auto after = std::lower_bound(samples_.begin(), samples_.end(), t_s,
                                [](const VehicleState& s, double t) { return s.t_s < t; });
  const VehicleState& a = *std::prev(after);
  const VehicleState& b = *after;
  const double w = (t_s - a.t_s) / (b.t_s - a.t_s);
  VehicleState s;
  s.t_s = t_s;
  s.pose = Pose2(a.pose.vector() + w * pose_difference(b.pose, a.pose));
  s.surge_mps = a.surge_mps + w * (b.surge_mps - a.surge_mps);
  s.sway_mps = a.sway_mps + w * (b.sway_mps - a.sway_mps);
  s.yaw_rate_radps = a.yaw_rate_radps + w * (b.yaw_rate_radps - a.yaw_rate_radps);
  return s;
}

namespace {

/// A polyline with arc-length parametrisation.
class Path {
 public:
  explicit Path(const std::vector<Eigen::Vector2d>& points) : points_(points) {
    arc_m_.push_back(0.0);
    for (std::size_t i = 1; i < points_.size(); ++i) {
      arc_m_.push_back(arc_m_.back() + (points_[i] - points_[i - 1]).norm());
    }
  }
  double length_m() const { return arc_m_.back(); }

  /// The leg (0-based) that holds arc length s_m.
  std::size_t leg_at(double s_m) const {
    const std::size_t i = std::upper_bound(arc_m_.begin(), arc_m_.end(), s_m) - arc_m_.begin();
    return std::clamp<std::size_t>(i, 1, points_.size() - 1) - 1;
  }

  Eigen::Vector2d point_at(double s_m) const {
    s_m = std::clamp(s_m, 0.0, length_m());
    std::size_t i = std::upper_bound(arc_m_.begin(), arc_m_.end(), s_m) - arc_m_.begin();
    i = std::clamp<std::size_t>(i, 1, points_.size() - 1);
    const double leg_m = arc_m_[i] - arc_m_[i - 1];
    const double w = leg_m > 0.0 ? (s_m - arc_m_[i - 1]) / leg_m : 0.0;
    return points_[i - 1] + w * (points_[i] - points_[i - 1]);
  }

  /// Arc length of the point of the path nearest to p among the legs that start before
  /// s_from_m + window_m, never behind s_from_m: the follower cannot jump back to an earlier pass.
  double progress(const Eigen::Vector2d& p, double s_from_m, double window_m) const {
    double best_s = s_from_m, best_d = (point_at(s_from_m) - p).squaredNorm();
    for (std::size_t i = 1; i < points_.size() && arc_m_[i - 1] <= s_from_m + window_m; ++i) {
      if (arc_m_[i] < s_from_m) continue;
      const Eigen::Vector2d leg = points_[i] - points_[i - 1];
      const double leg_m = arc_m_[i] - arc_m_[i - 1];
      if (leg_m <= 0.0) continue;
      const double w = std::clamp((p - points_[i - 1]).dot(leg) / (leg_m * leg_m), 0.0, 1.0);
      const double s = std::max(s_from_m, arc_m_[i - 1] + w * leg_m);
      const double d = (point_at(s) - p).squaredNorm();
      if (d < best_d) best_d = d, best_s = s;
    }
    return best_s;
  }

 private:
  std::vector<Eigen::Vector2d> points_;
  std::vector<double> arc_m_;
};

/// The motion over dt at constant speed and yaw rate, in the frame at the start of the step.
Pose2 arc_step(double speed_mps, double yaw_rate_radps, double dt_s) {
  const double dyaw = yaw_rate_radps * dt_s;
  if (std::abs(dyaw) < 1e-9) return Pose2(speed_mps * dt_s, 0.0, dyaw);
  const double radius_m = speed_mps / yaw_rate_radps;
  return Pose2(radius_m * std::sin(dyaw), radius_m * (1.0 - std::cos(dyaw)), dyaw);
}

}  // namespace

VehicleTrajectory follow_path(const VehicleConfig& config) {
  const Path path(config.path_m);
  const Eigen::Vector2d first_leg = config.path_m[1] - config.path_m[0];
  Pose2 pose(config.path_m[0].x(), config.path_m[0].y(), std::atan2(first_leg.y(), first_leg.x()));
  const double dt = config.step_s;
  // Turn-rate loop gain (1/s): the heading error decays in ~2 s unless the rate bound is hit.
  const double heading_gain = 0.5;
  const auto speed_at = [&](double s_m) {
    return config.leg_speeds_mps.empty() ? config.speed_mps
                                         : config.leg_speeds_mps[path.leg_at(s_m)];
  };
  double min_speed_mps = config.speed_mps;
  for (const double v : config.leg_speeds_mps) min_speed_mps = std::min(min_speed_mps, v);
  const double max_duration_s = 3.0 * path.length_m() / min_speed_mps + 60.0;
  std::vector<VehicleState> samples;
  double s_m = 0.0;
  for (double t = 0.0; t <= max_duration_s; t += dt) {
    s_m = path.progress(pose.translation(), s_m, 2.0 * config.lookahead_m);
    const Eigen::Vector2d carrot = path.point_at(s_m + config.lookahead_m);
    const Eigen::Vector2d to_carrot = carrot - pose.translation();
    const double heading_error =
        normalize_angle(std::atan2(to_carrot.y(), to_carrot.x()) - pose.yaw());
    const double r = std::clamp(heading_gain * heading_error, -config.max_turn_rate_radps,
                                config.max_turn_rate_radps);
    const double speed_mps = speed_at(s_m);
    samples.push_back({config.start_time_s + t, pose, speed_mps, 0.0, r});
    // Done once the nearest point of the path is its end: the vehicle is at or abeam of the last
    // waypoint (a last leg shorter than the turning circle cannot be reached any closer).
    if (path.length_m() - s_m < 0.5) break;
    // Exact integration of a constant-speed arc over dt.
    pose = pose.compose(arc_step(speed_mps, r, dt));
  }
  if (!config.heading_deg.empty()) {
    return with_heading(VehicleTrajectory(std::move(samples)), config.heading_deg);
  }
  return VehicleTrajectory(std::move(samples));
}

VehicleTrajectory with_heading(const VehicleTrajectory& course,
                               const std::vector<Eigen::Vector2d>& heading_deg) {
  if (heading_deg.size() < 2) {
    throw std::invalid_argument("with_heading: a heading history needs at least two rows");
  }
  const double start_s = course.start_s();
  std::size_t row = 0;
  // The heading at t (s from the start): the rows' yaw interpolated along the short arc.
  const auto yaw_at = [&](double t) {
    while (row + 2 < heading_deg.size() && heading_deg[row + 1].x() <= t) ++row;
    const Eigen::Vector2d& a = heading_deg[row];
    const Eigen::Vector2d& b = heading_deg[row + 1];
    const double w = std::clamp((t - a.x()) / (b.x() - a.x()), 0.0, 1.0);
    const double yaw_a = a.y() * M_PI / 180.0;
    return normalize_angle(yaw_a + w * normalize_angle(b.y() * M_PI / 180.0 - yaw_a));
  };
  std::vector<VehicleState> samples = course.samples();
  for (VehicleState& s : samples) {
    // World velocity of the course sample, then in the axes of the new heading.
    const Eigen::Vector2d v_world = s.pose.rotation() * Eigen::Vector2d(s.surge_mps, s.sway_mps);
    s.pose = Pose2(s.pose.x(), s.pose.y(), yaw_at(s.t_s - start_s));
    const Eigen::Vector2d v_vehicle = s.pose.rotation().transpose() * v_world;
    s.surge_mps = v_vehicle.x();
    s.sway_mps = v_vehicle.y();
  }
  for (std::size_t k = 0; k < samples.size(); ++k) {
    const VehicleState& before = samples[k == 0 ? 0 : k - 1];
    const VehicleState& after = samples[std::min(k + 1, samples.size() - 1)];
    const double dt = after.t_s - before.t_s;
    samples[k].yaw_rate_radps =
        dt > 0.0 ? normalize_angle(after.pose.yaw() - before.pose.yaw()) / dt : 0.0;
  }
  return VehicleTrajectory(std::move(samples));
}

}  // namespace msislab::sim
