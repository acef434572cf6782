#include "sim/scenario_checks.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <optional>

#include "geometry/angles.hpp"
#include "sim/scene_materials.hpp"
#include "sim/vehicle.hpp"

namespace msislab::sim {
namespace {

std::string format(const char* pattern, double a, double b = 0.0, double c = 0.0) {
  char text[96];
  std::snprintf(text, sizeof text, pattern, a, b, c);
  return text;
}

std::string xy(const Eigen::Vector2d& p) { return format("(%.1f, %.1f)", p.x(), p.y()); }

/// The first face of the mesh along a ray (the water surface does not count).
RayHit mesh_hit(const Scene& scene, const Eigen::Vector3d& origin_m,
                const Eigen::Vector3d& direction, double length_m) {
  Ray ray;
  ray.origin_m = origin_m.cast<float>();
  ray.direction = direction.cast<float>();
  ray.t_max_m = static_cast<float>(length_m);
  const RayHit hit = scene.intersect(ray);
  return hit.water_surface ? RayHit{} : hit;
}

/// How many mesh faces lie straight above origin_m, up to any height (the water surface
/// skipped): odd inside a closed solid, even under closed objects that float above the point.
int faces_above(const Scene& scene, const Eigen::Vector3d& origin_m) {
  constexpr double kStep_m = 1e-3;  // past each face before looking for the next
  constexpr int kMaxFaces = 64;
  Ray ray;
  ray.origin_m = origin_m.cast<float>();
  ray.direction = Eigen::Vector3f::UnitZ();
  ray.t_max_m = 1e6f;
  int faces = 0;
  for (int k = 0; k < kMaxFaces; ++k) {
    const RayHit hit = scene.intersect(ray);
    if (!hit.hit) break;
    if (!hit.water_surface) ++faces;
    ray.origin_m.z() += hit.distance_m + static_cast<float>(kStep_m);
  }
  return faces;
}

std::string group_of(const Scene& scene, const RayHit& hit) {
  return "'" + scene.materials()[hit.material_id].name + "'";
}

/// The lowest altitude met along the path, and where.
struct LowestPoint {
  double altitude_m = std::numeric_limits<double>::infinity();
  std::string where;
};

/// One leg, from waypoint `from` to from + 1, with the findings it makes.
class LegCheck {
 public:
  LegCheck(const VehicleConfig& vehicle, const Scene& scene, const ScenarioCheckConfig& config,
           std::size_t from)
      : v_(vehicle), scene_(scene), config_(config), from_(from) {
    // Just under the surface for a vehicle at depth 0, so no ray runs inside the surface plane.
    z_m_ = -std::max(vehicle.depth_m, 0.01);
    a_ = vehicle.path_m[from];
    b_ = vehicle.path_m[from + 1];
  }

  /// The leg's first error, or its warnings; updates `lowest`.
  std::vector<ScenarioFinding> run(LowestPoint& lowest) {
    length_m_ = (b_ - a_).norm();
    along_ = (b_ - a_) / length_m_;
    const std::vector<RayHit> faces = faces_along();
    points_ =
        std::max<std::size_t>(1, static_cast<std::size_t>(std::ceil(length_m_ / config_.step_m)));
    for (std::size_t j = 0; j <= points_; ++j) {
      const double t_m = length_m_ * static_cast<double>(j) / static_cast<double>(points_);
      std::optional<ScenarioFinding> error = check_point(a_ + t_m * along_, j, lowest);
      if (!error) continue;
      // Out of the water beyond a face of the mesh: the face crossed is what went wrong. A point
      // on the face itself (within the float hit's precision) is not beyond it: whether a ray
      // there meets the face depends on the CPU's kernels, not on the scenario.
      constexpr double kOnFace_m = 1e-3;
      if (!faces.empty() && faces.front().distance_m < t_m - kOnFace_m) {
        error = ScenarioFinding{
            ScenarioKey::kWaypoint, from_ + 1, true,
            leg() + " crosses the mesh " + face_at(faces.front()) + ", and leaves the water", ""};
      }
      return {*error};
    }
    std::vector<ScenarioFinding> out;
    if (auto through = passage(faces)) out.push_back(*through);
    if (nearest_wall_m_ < config_.wall_clearance_m && out.empty()) {
      out.push_back({ScenarioKey::kWaypoint, from_ + 1, false,
                     leg() + format(" passes %.2f m from the mesh", nearest_wall_m_) + " (group " +
                         nearest_group_ + ") at " + xy(nearest_at_) +
                         format(", closer than the %.1f m clearance", config_.wall_clearance_m),
                     "wall_clearance"});
    }
    return out;
  }

 private:
  Eigen::Vector3d at(const Eigen::Vector2d& p) const { return {p.x(), p.y(), z_m_}; }

  std::string waypoint(std::size_t i) const {
    return "waypoint " + std::to_string(i + 1) + " " + xy(v_.path_m[i]);
  }
  std::string leg() const {
    return "the leg from " + waypoint(from_) + " to " + waypoint(from_ + 1);
  }
  /// Every face along the leg at the vehicle's depth, nearest first.
  std::vector<RayHit> faces_along() const {
    std::vector<RayHit> faces;
    double t_m = 0.0;
    while (faces.size() < 64) {
      RayHit hit =
          mesh_hit(scene_, at(a_ + t_m * along_), {along_.x(), along_.y(), 0.0}, length_m_ - t_m);
      if (!hit.hit) break;
      hit.distance_m += static_cast<float>(t_m);
      faces.push_back(hit);
      t_m = hit.distance_m + 1e-3;
    }
    return faces;
  }

  std::string face_at(const RayHit& face) const {
    return "(group " + group_of(scene_, face) + ") at " +
           xy(a_ + static_cast<double>(face.distance_m) * along_) + format(", %.1f m deep", -z_m_);
  }

  /// The longest stretch of the leg inside an object (faces paired: in, out, in, ...).
  std::optional<ScenarioFinding> passage(const std::vector<RayHit>& faces) const {
    if (faces.empty()) return std::nullopt;
    double longest_m = -1.0;
    std::size_t entry = 0;
    for (std::size_t k = 0; k < faces.size(); k += 2) {
      const double out_m = k + 1 < faces.size() ? faces[k + 1].distance_m : length_m_;
      if (out_m - faces[k].distance_m <= longest_m) continue;
      longest_m = out_m - faces[k].distance_m;
      entry = k;
    }
    return ScenarioFinding{ScenarioKey::kWaypoint, from_ + 1, false,
                           leg() + format(" runs %.2f m through the mesh ", longest_m) +
                               face_at(faces[entry]) +
                               ": the simulator has no collisions, the vehicle passes through it",
                           "through_object"};
  }

  /// Point j of the leg's points_ + 1.
  std::string where(const Eigen::Vector2d& p, std::size_t j) const {
    if (j == 0) return waypoint(from_);
    if (j == points_) return waypoint(from_ + 1);
    return xy(p) + " on " + leg();
  }

  std::optional<ScenarioFinding> check_point(const Eigen::Vector2d& p, std::size_t j,
                                             LowestPoint& lowest) {
    const std::size_t key_index = j == 0 ? from_ : from_ + 1;
    // Something under the surface above the vehicle is an error when the vehicle is below the
    // floor (nothing under it) or inside a closed solid (an odd count of faces above); under a
    // closed object that floats (a moored hull: an even count) it is where the real vehicle was.
    const RayHit up = mesh_hit(scene_, at(p), Eigen::Vector3d::UnitZ(), -z_m_);
    const RayHit down = mesh_hit(scene_, at(p), -Eigen::Vector3d::UnitZ(), 1e6);
    if (up.hit && (!down.hit || faces_above(scene_, at(p)) % 2 == 1)) {
      return ScenarioFinding{ScenarioKey::kDepth, 0, true,
                             format("%g m puts the vehicle under the mesh (group ", v_.depth_m) +
                                 group_of(scene_, up) +
                                 format(" at %.2f m depth) at ", -z_m_ - up.distance_m) +
                                 where(p, j) + ": below the floor or inside a solid",
                             ""};
    }
    if (!down.hit) {
      return ScenarioFinding{ScenarioKey::kWaypoint, key_index, true,
                             where(p, j) + " has no floor under it: the path leaves the scene", ""};
    }
    if (down.distance_m < lowest.altitude_m) lowest = {down.distance_m, where(p, j)};
    for (int k = 0; k < config_.directions; ++k) {
      const double angle = 2.0 * kPi * k / config_.directions;
      const RayHit side = mesh_hit(scene_, at(p), {std::cos(angle), std::sin(angle), 0.0},
                                   config_.wall_clearance_m);
      const double max_cos = std::cos(kMaxBottomTilt_deg * kPi / 180.0);
      if (!side.hit || std::abs(side.normal.z()) >= max_cos || side.distance_m >= nearest_wall_m_)
        continue;
      nearest_wall_m_ = side.distance_m;
      nearest_at_ = p;
      nearest_group_ = group_of(scene_, side);
    }
    return std::nullopt;
  }

  const VehicleConfig& v_;
  const Scene& scene_;
  const ScenarioCheckConfig& config_;
  std::size_t from_;
  double z_m_ = 0.0;
  Eigen::Vector2d a_, b_;
  double length_m_ = 0.0;
  Eigen::Vector2d along_ = Eigen::Vector2d::UnitX();
  std::size_t points_ = 1;
  double nearest_wall_m_ = std::numeric_limits<double>::infinity();
  Eigen::Vector2d nearest_at_ = Eigen::Vector2d::Zero();
  std::string nearest_group_;
};

}  // namespace

std::vector<ScenarioFinding> check_path(const VehicleConfig& vehicle, const Scene& scene,
                                        const ScenarioCheckConfig& config) {
  std::vector<ScenarioFinding> out;
  LowestPoint lowest;
  for (std::size_t i = 0; i + 1 < vehicle.path_m.size(); ++i) {
    for (ScenarioFinding& f : LegCheck(vehicle, scene, config, i).run(lowest)) {
      out.push_back(std::move(f));
    }
  }
  const bool any_error =
      std::any_of(out.begin(), out.end(), [](const ScenarioFinding& f) { return f.error; });
  if (!any_error && lowest.altitude_m < config.bottom_clearance_m) {
    out.push_back({ScenarioKey::kDepth, 0, false,
                   format("%g m leaves the vehicle %.2f m above the floor at ", vehicle.depth_m,
                          lowest.altitude_m) +
                       lowest.where +
                       format(", under the %.1f m clearance", config.bottom_clearance_m),
                   "bottom_clearance"});
  }
  return out;
}

std::vector<ScenarioFinding> check_segments(const std::vector<TimeSegment>& segments,
                                            double duration_s) {
  std::vector<ScenarioFinding> out;
  for (std::size_t i = 0; i < segments.size(); ++i) {
    const TimeSegment& s = segments[i];
    if (s.begin_s >= duration_s) {
      out.push_back({ScenarioKey::kSegment, i, true,
                     format("[%g, %g] s begins after the run, which lasts %.1f s: nothing to score",
                            s.begin_s, s.end_s, duration_s),
                     ""});
    } else if (s.end_s - duration_s > 0.5 * (s.end_s - s.begin_s)) {
      out.push_back({ScenarioKey::kSegment, i, false,
                     format("[%g, %g] s ends after the run, which lasts %.1f s: ", s.begin_s,
                            s.end_s, duration_s) +
                         format("less than half of it is scored (%.0f s of %.0f)",
                                duration_s - s.begin_s, s.end_s - s.begin_s),
                     "segment_after_run"});
    }
  }
  return out;
}

std::vector<ScenarioFinding> check_scenario(const Scenario& scenario, const Scene& scene,
                                            const ScenarioCheckConfig& config) {
  std::vector<ScenarioFinding> out = check_path(scenario.vehicle, scene, config);
  const VehicleTrajectory truth = follow_path(scenario.vehicle);
  for (ScenarioFinding& f : check_segments(scenario.segments, truth.end_s() - truth.start_s())) {
    out.push_back(std::move(f));
  }
  return out;
}

}  // namespace msislab::sim
