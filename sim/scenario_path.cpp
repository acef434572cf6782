#include "sim/scenario_path.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

namespace msislab::sim {

SceneOutline outline_of(const TriangleMesh& mesh) {
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
    throw std::invalid_argument("needs the groups 'walls' and 'bottom'");
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

Eigen::Vector2d nearest_wall_point(const SceneOutline& outline, const Eigen::Vector2d& p) {
  Eigen::Vector2d nearest = outline.walls.front().first;
  for (const auto& [a, b] : outline.walls) {
    const double u = std::clamp((p - a).dot(b - a) / (b - a).squaredNorm(), 0.0, 1.0);
    const Eigen::Vector2d q = a + u * (b - a);
    if ((q - p).squaredNorm() < (nearest - p).squaredNorm()) nearest = q;
  }
  return nearest;
}

double clearance_m(const SceneOutline& outline, const Eigen::Vector2d& p) {
  const double distance_m = (nearest_wall_point(outline, p) - p).norm();
  return inside(outline, p) ? distance_m : -distance_m;
}

double pull_inside(const SceneOutline& outline, Eigen::Vector2d& p, double wanted_m) {
  const Eigen::Vector2d start = p;
  for (int iteration = 0; iteration < 20 && clearance_m(outline, p) < wanted_m; ++iteration) {
    const Eigen::Vector2d q = nearest_wall_point(outline, p);
    const Eigen::Vector2d inward = (inside(outline, p) ? p - q : q - p).normalized();
    p = q + inward * (wanted_m + 0.05);
  }
  return (p - start).norm();
}

double min_leg_clearance_m(const SceneOutline& outline, const Path2& path) {
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

bool path_enters(const Path2& path, const Path2& ccw_convex_polygon) {
  const auto inside = [&](const Eigen::Vector2d& p) {
    for (std::size_t i = 0; i < ccw_convex_polygon.size(); ++i) {
      const Eigen::Vector2d& a = ccw_convex_polygon[i];
      const Eigen::Vector2d edge = ccw_convex_polygon[(i + 1) % ccw_convex_polygon.size()] - a;
      const Eigen::Vector2d to_p = p - a;
      if (edge.x() * to_p.y() - edge.y() * to_p.x() < 0.0) return false;
    }
    return true;
  };
  for (std::size_t i = 1; i < path.size(); ++i) {
    const int samples = 1 + static_cast<int>((path[i] - path[i - 1]).norm() / 0.25);
    for (int k = 0; k <= samples; ++k) {
      if (inside(path[i - 1] + (path[i] - path[i - 1]) * k / samples)) return true;
    }
  }
  return false;
}

Path2 smooth_track(const std::vector<double>& t_s, const Path2& p_m, double window_s) {
  Path2 smoothed;
  std::size_t lo = 0, hi = 0;
  for (std::size_t k = 0; k < t_s.size(); ++k) {
    const double half_s = std::min({window_s / 2.0, t_s[k] - t_s.front(), t_s.back() - t_s[k]});
    while (t_s[lo] < t_s[k] - half_s) ++lo;
    while (hi + 1 < t_s.size() && t_s[hi + 1] <= t_s[k] + half_s) ++hi;
    Eigen::Vector2d sum = Eigen::Vector2d::Zero();
    for (std::size_t i = lo; i <= hi; ++i) sum += p_m[i];
    smoothed.push_back(sum / static_cast<double>(hi - lo + 1));
  }
  return smoothed;
}

std::vector<std::size_t> simplify(const Path2& path, double tolerance_m) {
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

double length_m(const Path2& path) {
  double total_m = 0.0;
  for (std::size_t i = 1; i < path.size(); ++i) total_m += (path[i] - path[i - 1]).norm();
  return total_m;
}

std::vector<double> arrival_times_s(const VehicleTrajectory& truth, const Path2& path) {
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

std::pair<std::vector<double>, std::vector<double>> timed_leg_speeds(
    const Path2& path, const std::vector<double>& real_times_s, int iterations) {
  VehicleConfig vehicle;
  vehicle.path_m = path;
  for (std::size_t k = 1; k < path.size(); ++k) {
    const double leg_s = std::max(real_times_s[k] - real_times_s[k - 1], 1.0);
    vehicle.leg_speeds_mps.push_back(std::clamp((path[k] - path[k - 1]).norm() / leg_s, 0.02, 1.0));
  }
  std::vector<double> arrivals;
  for (int iteration = 0; iteration <= iterations; ++iteration) {
    arrivals = arrival_times_s(follow_path(vehicle), path);
    if (iteration == iterations) break;
    for (std::size_t k = 1; k < path.size(); ++k) {
      const double simulated_s = std::max(arrivals[k] - arrivals[k - 1], 1.0);
      const double real_s = std::max(real_times_s[k] - real_times_s[k - 1], 1.0);
      vehicle.leg_speeds_mps[k - 1] =
          std::clamp(vehicle.leg_speeds_mps[k - 1] * simulated_s / real_s, 0.02, 1.0);
    }
  }
  return {vehicle.leg_speeds_mps, arrivals};
}

}  // namespace msislab::sim
