// The statistics of navigation_statistics.hpp that compare the dead reckoning with positions:
// drift per distance, the heading offset, and the GPS buoy's lag, tether and error.
#include <algorithm>
#include <cassert>
#include <cmath>
#include <functional>

#include "eval/evaluation.hpp"
#include "eval/navigation_statistics.hpp"
#include "geometry/angles.hpp"
#include "geometry/se2.hpp"
#include "sim/navigation_sensors.hpp"
#include "stats/sample_statistics.hpp"

namespace msislab {

namespace {

/// The measurements between t0_s and t1_s (inclusive).
NavigationLog slice(const NavigationLog& log, double t0_s, double t1_s) {
  NavigationLog out;
  std::copy_if(log.dvl.begin(), log.dvl.end(), std::back_inserter(out.dvl),
               [&](const DvlVelocity& d) { return d.t_s >= t0_s && d.t_s <= t1_s; });
  std::copy_if(log.heading.begin(), log.heading.end(), std::back_inserter(out.heading),
               [&](const HeadingReading& h) { return h.t_s >= t0_s && h.t_s <= t1_s; });
  return out;
}

/// Dead reckoning from a truth position at t0_s with the MRU heading, up to t1_s.
std::vector<StampedPose> dead_reckon(const NavigationLog& log, const PositionFix& start,
                                     double t1_s, const Eigen::Vector2d& p_vehicle_dvl_m,
                                     bool use_ekf, const DeadReckoningConfig& ekf) {
  const NavigationLog part = slice(log, start.t_s - 1.0, t1_s + 1.0);
  if (part.heading.empty()) return {};
  StampedPose initial;
  initial.t_s = start.t_s;
  initial.pose.mean = Pose2(start.p_world_m.x(), start.p_world_m.y(),
                            nearest_heading(part.heading, start.t_s).yaw_rad);
  initial.pose.cov = Eigen::Vector3d(1e-9, 1e-9, std::pow(ekf.heading_sigma_rad, 2)).asDiagonal();
  if (!use_ekf) return integrate_velocities(part, initial);
  return run_dead_reckoning(part, ekf, p_vehicle_dvl_m, initial).trajectory;
}

/// Path length at each truth sample, counting steps of at least step_m.
std::vector<double> path_length(const std::vector<PositionFix>& truth, double step_m) {
  std::vector<double> s = {0.0};
  Eigen::Vector2d anchor = truth.front().p_world_m;
  for (std::size_t i = 1; i < truth.size(); ++i) {
    const double step = (truth[i].p_world_m - anchor).norm();
    s.push_back(s.back() + (step >= step_m ? step : 0.0));
    if (step >= step_m) anchor = truth[i].p_world_m;
  }
  return s;
}

/// Index of the first sample at or after `from` whose path length reaches s_m; size() if none.
std::size_t index_at_path(const std::vector<double>& s, std::size_t from, double s_m) {
  return static_cast<std::size_t>(
      std::lower_bound(s.begin() + static_cast<long>(from), s.end(), s_m) - s.begin());
}

/// Rms per axis of GPS(t) - track(t - shift_s) after removing each window's mean offset.
double windowed_residual(const std::vector<PositionFix>& gps, const std::vector<PositionFix>& track,
                         double shift_s, double window_s) {
  double sum_sq = 0.0;
  std::size_t count = 0;
  for (std::size_t i = 0; i < gps.size();) {
    std::vector<Eigen::Vector2d> e;
    std::size_t j = i;
    for (; j < gps.size() && gps[j].t_s < gps[i].t_s + window_s; ++j) {
      const double t = gps[j].t_s - shift_s;
      if (t < track.front().t_s || t > track.back().t_s) continue;
      e.push_back(gps[j].p_world_m - interpolate_position(track, t));
    }
    i = j;
    if (e.size() < 2) continue;
    Eigen::Vector2d mean = Eigen::Vector2d::Zero();
    for (const auto& v : e) mean += v / static_cast<double>(e.size());
    for (const auto& v : e) sum_sq += (v - mean).squaredNorm();
    count += e.size() - 1;
  }
  return count ? std::sqrt(sum_sq / (2.0 * static_cast<double>(count))) : 0.0;
}

/// The argument in [lo, hi] (grid step `step`) minimising f, refined by a parabola through the
/// best grid point and its neighbours.
std::pair<double, double> minimise(const std::function<double(double)>& f, double lo, double hi,
                                   double step) {
  std::vector<double> x, y;
  for (double v = lo; v <= hi + 1e-9; v += step) x.push_back(v), y.push_back(f(v));
  const auto k = static_cast<std::size_t>(std::min_element(y.begin(), y.end()) - y.begin());
  if (k == 0 || k + 1 == y.size()) return {x[k], y[k]};
  const double curvature = y[k - 1] - 2.0 * y[k] + y[k + 1];
  const double offset = curvature > 0.0 ? 0.5 * (y[k - 1] - y[k + 1]) / curvature : 0.0;
  return {x[k] + offset * step, y[k]};
}

}  // namespace

DriftStatistics dead_reckoning_drift(const NavigationLog& navigation,
                                     const std::vector<PositionFix>& truth,
                                     const Eigen::Vector2d& p_vehicle_dvl_m,
                                     const DriftOptions& options) {
  DriftStatistics stats;
  if (truth.size() < 2 || navigation.heading.empty()) return stats;
  const std::vector<double> s = path_length(truth, options.path_step_m);
  for (double s0 = 0.0; s0 + options.window_m <= s.back(); s0 += options.stride_m) {
    const std::size_t i0 = index_at_path(s, 0, s0);
    const std::size_t i1 = index_at_path(s, i0, s[i0] + options.window_m);
    if (i1 >= truth.size() || truth[i0].t_s < navigation.heading.front().t_s) continue;
    const std::vector<StampedPose> dr = dead_reckon(navigation, truth[i0], truth[i1].t_s,
                                                    p_vehicle_dvl_m, options.use_ekf, options.ekf);
    if (dr.empty() || dr.back().t_s < truth[i1].t_s) continue;
    const Pose2 end = interpolate_pose(dr, truth[i1].t_s);
    stats.end_error_m.push_back((end.translation() - truth[i1].p_world_m).norm());
  }
  if (stats.end_error_m.empty()) return stats;
  for (const double e : stats.end_error_m) stats.mean_m += e / double(stats.end_error_m.size());
  stats.p90_m = quantile(stats.end_error_m, 0.9);
  return stats;
}

HeadingOffsetStatistics heading_offset_statistics(const NavigationLog& navigation,
                                                  const std::vector<PositionFix>& truth,
                                                  const Eigen::Vector2d& p_vehicle_dvl_m,
                                                  double window_m) {
  HeadingOffsetStatistics stats;
  if (truth.size() < 2 || navigation.heading.empty()) return stats;
  const std::vector<double> s = path_length(truth, 1.0);
  for (std::size_t i0 = 0;;) {
    const std::size_t i1 = index_at_path(s, i0, s[i0] + window_m);
    if (i1 >= truth.size()) break;
    const std::vector<StampedPose> dr =
        dead_reckon(navigation, truth[i0], truth[i1].t_s, p_vehicle_dvl_m, true, {});
    if (!dr.empty() && truth[i0].t_s >= navigation.heading.front().t_s) {
      // Centred Procrustes rotation taking the dead-reckoned points onto the truth points.
      Eigen::Vector2d mean_dr = Eigen::Vector2d::Zero(), mean_truth = Eigen::Vector2d::Zero();
      std::vector<Eigen::Vector2d> p_dr;
      for (std::size_t i = i0; i <= i1; ++i) {
        p_dr.push_back(interpolate_pose(dr, truth[i].t_s).translation());
        mean_dr += p_dr.back();
        mean_truth += truth[i].p_world_m;
      }
      mean_dr /= static_cast<double>(p_dr.size());
      mean_truth /= static_cast<double>(p_dr.size());
      double dot = 0.0, cross = 0.0;
      for (std::size_t i = i0; i <= i1; ++i) {
        const Eigen::Vector2d a = p_dr[i - i0] - mean_dr, b = truth[i].p_world_m - mean_truth;
        dot += a.dot(b);
        cross += a.x() * b.y() - a.y() * b.x();
      }
      stats.window_offset_deg.push_back(-std::atan2(cross, dot) * kRadToDeg);
    }
    i0 = i1;
  }
  const std::vector<double>& w = stats.window_offset_deg;
  const auto n = static_cast<double>(w.size());
  if (w.size() < 2) return stats;
  for (const double v : w) stats.mean_deg += v / n;
  double var = 0.0, consecutive = 0.0;
  for (const double v : w) var += (v - stats.mean_deg) * (v - stats.mean_deg) / (n - 1.0);
  for (std::size_t i = 1; i < w.size(); ++i) consecutive += std::pow(w[i] - w[i - 1], 2) / (n - 1);
  stats.sd_deg = std::sqrt(var);
  stats.standard_error_deg = stats.sd_deg / std::sqrt(n);
  stats.consecutive_sd_deg = std::sqrt(consecutive / 2.0);
  stats.median_deg = median(w);
  return stats;
}

std::vector<PositionFix> towed_buoy(const std::vector<PositionFix>& vehicle, double tether_m) {
  std::vector<PositionFix> buoy;
  if (vehicle.empty()) return buoy;
  Eigen::Vector2d p_buoy = vehicle.front().p_world_m;
  for (const PositionFix& v : vehicle) {
    p_buoy = sim::drag_buoy(p_buoy, v.p_world_m, tether_m);
    buoy.push_back({v.t_s, p_buoy});
  }
  return buoy;
}

GpsStatistics gps_statistics(const NavigationLog& navigation, const std::vector<PositionFix>& gps,
                             const Eigen::Vector2d& p_vehicle_dvl_m, const GpsOptions& options) {
  GpsStatistics stats;
  std::vector<double> x, y, dt;
  for (std::size_t i = 0; i < gps.size(); ++i) {
    x.push_back(gps[i].p_world_m.x());
    y.push_back(gps[i].p_world_m.y());
    if (i > 0) dt.push_back(gps[i].t_s - gps[i - 1].t_s);
  }
  stats.rate_hz = 1.0 / median(dt);
  stats.white_x_m = difference_noise(x, 2);
  stats.white_y_m = difference_noise(y, 2);
  // The vehicle track: the EKF dead reckoning from the first fix with an MRU heading.
  NavigationLog corrected = navigation;
  for (HeadingReading& h : corrected.heading) {
    h.yaw_rad = normalize_angle(h.yaw_rad - options.heading_offset_deg / kRadToDeg);
  }
  auto first = std::find_if(gps.begin(), gps.end(), [&](const PositionFix& f) {
    return f.t_s >= navigation.heading.front().t_s;
  });
  assert(first != gps.end());
  std::vector<PositionFix> vehicle;
  for (const StampedPose& p :
       dead_reckon(corrected, *first, gps.back().t_s, p_vehicle_dvl_m, true, {})) {
    vehicle.push_back({p.t_s, p.pose.mean.translation()});
  }
  std::tie(stats.lag_s, stats.lag_residual_m) =
      minimise([&](double lag) { return windowed_residual(gps, vehicle, lag, options.window_s); },
               -10.0, options.max_lag_s, 0.5);
  std::tie(stats.tether_m, stats.tether_residual_m) = minimise(
      [&](double L) {
        return windowed_residual(gps, towed_buoy(vehicle, L), 0.0, options.window_s);
      },
      0.0, options.max_tether_m, 0.1);
  // Structure function of the GPS error against the towed-buoy dead reckoning.
  const std::vector<PositionFix> buoy = towed_buoy(vehicle, stats.tether_m);
  for (const double lag_s : options.structure_lags_s) {
    double sum = 0.0;
    std::size_t count = 0;
    for (std::size_t i = 0, j = 0; i < gps.size(); ++i) {
      if (gps[i].t_s < buoy.front().t_s) continue;
      while (j < gps.size() && gps[j].t_s < gps[i].t_s + lag_s - 0.25 / stats.rate_hz) ++j;
      if (j >= gps.size() || gps[j].t_s > gps[i].t_s + lag_s + 0.25 / stats.rate_hz) continue;
      if (gps[j].t_s > buoy.back().t_s) break;
      const Eigen::Vector2d e_i = gps[i].p_world_m - interpolate_position(buoy, gps[i].t_s);
      const Eigen::Vector2d e_j = gps[j].p_world_m - interpolate_position(buoy, gps[j].t_s);
      sum += 0.25 * (e_j - e_i).squaredNorm();
      ++count;
    }
    stats.structure_m2.push_back(count ? sum / static_cast<double>(count) : 0.0);
  }
  return stats;
}

}  // namespace msislab
