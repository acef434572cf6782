#include "sim/msis.hpp"

#include <algorithm>
#include <cmath>

#include "geometry/angles.hpp"
#include "geometry/calibration.hpp"
#include "sim/sonar_physics.hpp"

namespace msislab::sim {

namespace {

Eigen::Vector3f direction(double azimuth_rad, double elevation_rad) {
  return Eigen::Vector3f(static_cast<float>(std::cos(elevation_rad) * std::cos(azimuth_rad)),
                         static_cast<float>(std::cos(elevation_rad) * std::sin(azimuth_rad)),
                         static_cast<float>(std::sin(elevation_rad)));
}

/// d direction / d azimuth and d direction / d elevation.
Eigen::Vector3f direction_d_azimuth(double azimuth_rad, double elevation_rad) {
  return Eigen::Vector3f(static_cast<float>(-std::cos(elevation_rad) * std::sin(azimuth_rad)),
                         static_cast<float>(std::cos(elevation_rad) * std::cos(azimuth_rad)), 0.0f);
}
Eigen::Vector3f direction_d_elevation(double azimuth_rad, double elevation_rad) {
  return Eigen::Vector3f(static_cast<float>(-std::sin(elevation_rad) * std::cos(azimuth_rad)),
                         static_cast<float>(-std::sin(elevation_rad) * std::sin(azimuth_rad)),
                         static_cast<float>(std::cos(elevation_rad)));
}

/// Rotation about z by the beam axis azimuth (cos, sin).
Eigen::Vector3f rotate_z(const Eigen::Vector3f& v, float c, float s) {
  return Eigen::Vector3f(c * v.x() - s * v.y(), s * v.x() + c * v.y(), v.z());
}

Eigen::Vector3f mirror(const Eigen::Vector3f& v, const Eigen::Vector3f& normal) {
  return v - 2.0f * v.dot(normal) * normal;
}

}  // namespace

std::vector<BeamSlot> beam_schedule(const SonarConfig& sonar, double t_begin_s, double t_end_s) {
  const double period_s = sonar.revolution_s / sonar.steps_per_revolution;
  const double step_rad = 2.0 * M_PI / sonar.steps_per_revolution;
  const auto n = static_cast<std::int64_t>(sonar.steps_per_revolution);
  const std::int64_t direction = sonar.rotation == SonarRotation::kIncreasing ? 1 : -1;
  const auto wrap = [n](std::int64_t i) { return ((i % n) + n) % n; };
  // A sector: its sweep is m steps long in the rotation's direction; beam k lies p steps from
  // the first index, p running 0..m then back down to 1 (a triangle wave of period 2m).
  const std::int64_t first = sonar.sector ? sonar.sector->first_index : 0;
  const std::int64_t m =
      sonar.sector ? wrap(direction * (sonar.sector->last_index - sonar.sector->first_index)) : 0;
  std::vector<BeamSlot> slots;
  for (std::uint64_t k = 0;; ++k) {
    const double t_s = t_begin_s + static_cast<double>(k) * period_s;
    if (t_s > t_end_s) break;
    std::int64_t steps = static_cast<std::int64_t>(k % static_cast<std::uint64_t>(n));
    if (m > 0) {
      const std::int64_t phase = static_cast<std::int64_t>(k % static_cast<std::uint64_t>(2 * m));
      steps = phase <= m ? phase : 2 * m - phase;
    }
    const std::int64_t angle_index = wrap(first + direction * steps);
    slots.push_back({k, t_s, static_cast<double>(angle_index) * step_rad});
  }
  return slots;
}

std::vector<MsisModel::RayTemplate> MsisModel::aperture_rays(const SonarConfig& sonar) {
  const double h_width = sonar.horizontal_beamwidth_deg * kDegToRad;
  const double v_width = sonar.vertical_beamwidth_deg * kDegToRad;
  // Rays at the centres of equal cells spanning +-span beamwidths around the axis, each weighted
  // by the one-way pattern and its cell's share of the aperture.
  const double h_half = h_width * sonar.horizontal_span_beamwidths;
  const double v_half = v_width * sonar.vertical_span_beamwidths;
  const double h_cell = 2.0 * h_half / sonar.rays_horizontal;
  const double v_cell = 2.0 * v_half / sonar.rays_vertical;
  std::vector<RayTemplate> rays;
  for (int i = 0; i < sonar.rays_horizontal; ++i) {
    for (int j = 0; j < sonar.rays_vertical; ++j) {
      RayTemplate ray;
      ray.azimuth_rad = -h_half + (i + 0.5) * h_cell;
      ray.elevation_rad = -v_half + (j + 0.5) * v_cell;
      ray.weight = one_way_pattern(ray.azimuth_rad, ray.elevation_rad, sonar);
      const double e_rad = ray.elevation_rad - sonar.tilt_deg * kDegToRad;
      ray.direction_beam = direction(ray.azimuth_rad, e_rad);
      ray.cell_azimuth_beam = direction_d_azimuth(ray.azimuth_rad, e_rad) * h_cell;
      ray.cell_elevation_beam = direction_d_elevation(ray.azimuth_rad, e_rad) * v_cell;
      ray.cell_sr = h_cell * v_cell * std::cos(e_rad);
      rays.push_back(ray);
    }
  }
  return rays;
}

namespace {
/// Point scatterers: the norm that makes the two-way weights sum to 1, so a plane filling the
/// beam at normal incidence returns its backscatter times the loss. Footprints: 1, the weights
/// stay the pattern itself, since sum b^2 x cell solid angle already approximates the beam's
/// integral of b^2 over solid angle, the same for any number of rays.
template <typename Rays>
double pattern_norm_of(const Rays& rays, const SonarConfig& sonar) {
  if (sonar.footprint) return 1.0;
  double total = 0.0;
  for (const auto& ray : rays) total += ray.weight * ray.weight;
  return std::sqrt(total);
}
}  // namespace

MsisModel::MsisModel(const Scene& scene, const SonarConfig& sonar, double vehicle_depth_m)
    : scene_(scene),
      sonar_(sonar),
      depth_m_(vehicle_depth_m),
      rays_(aperture_rays(sonar)),
      pattern_norm_(pattern_norm_of(rays_, sonar)),
      receiver_(sonar, pattern_norm_) {
  for (RayTemplate& ray : rays_) ray.weight /= pattern_norm_;
}

SonarHead MsisModel::head_at(double t_s, const VehicleTrajectory& trajectory,
                             double bearing_vehicle_rad) const {
  const Pose2 vehicle = trajectory.at(t_s).pose;
  const Eigen::Vector2d p = vehicle.transform({sonar_.mount.x_m, sonar_.mount.y_m});
  const double azimuth_rad = vehicle.yaw() + bearing_vehicle_rad;
  return {Eigen::Vector3f(static_cast<float>(p.x()), static_cast<float>(p.y()),
                          static_cast<float>(-depth_m_ + sonar_.mount.z_m)),
          azimuth_rad, Eigen::Vector2d(std::cos(azimuth_rad), std::sin(azimuth_rad))};
}

Ping MsisModel::ping_of(const BeamSlot& slot, const VehicleTrajectory& trajectory) const {
  Ping ping;
  ping.t_s = slot.t_s;
  ping.bearing_vehicle_rad = sonar_bearing_in_vehicle(slot.transducer_angle_rad, sonar_.mount);
  ping.tx = head_at(slot.t_s, trajectory, ping.bearing_vehicle_rad);
  ping.rx_window_s = 2.0 * sonar_.bins * sonar_.bin_m / sonar_.sound_speed_mps;
  ping.rx_last = head_at(slot.t_s + ping.rx_window_s, trajectory, ping.bearing_vehicle_rad);
  return ping;
}

void MsisModel::primary_rays(const Ping& ping, std::vector<Ray>& rays) const {
  // Template directions (beam frame, axis along x, tilt applied) rotated to the axis azimuth.
  const float c = static_cast<float>(ping.tx.axis.x()), s = static_cast<float>(ping.tx.axis.y());
  rays.resize(rays_.size());
  for (std::size_t i = 0; i < rays_.size(); ++i) {
    rays[i].origin_m = ping.tx.position_m;
    rays[i].direction = rotate_z(rays_[i].direction_beam, c, s);
    rays[i].t_max_m = static_cast<float>(max_physical_range_m(sonar_));
  }
}

std::vector<Ray> MsisModel::primary_rays(const BeamSlot& slot,
                                         const VehicleTrajectory& trajectory) const {
  std::vector<Ray> rays;
  primary_rays(ping_of(slot, trajectory), rays);
  return rays;
}

struct MsisModel::Route {
  const RayTemplate* ray = nullptr;
  Eigen::Vector3f first_hit_m = Eigen::Vector3f::Zero();
  /// The ray's cell of the aperture as two edge vectors of its direction; a planar mirror keeps
  /// the cell's shape, so they are mirrored with the ray.
  Eigen::Vector3f cell_azimuth = Eigen::Vector3f::Zero();
  Eigen::Vector3f cell_elevation = Eigen::Vector3f::Zero();
  double path_m = 0.0;
  double route_gain = 0.0;  ///< transmit pattern x specular factors of both ways
};

struct MsisModel::Workspace {
  std::vector<Ray> rays;
  std::vector<RayHit> hits;
  std::vector<Route> routes;  ///< the routes the rays in `rays` continue
  std::vector<Echo> echoes;   ///< of one bounce, in the order of the routes
  EchoProfile profile;
  ReceiverScratch receiver;
};

RenderedBeam MsisModel::render(const BeamSlot& slot, const VehicleTrajectory& trajectory,
                               Rng& rng) const {
  return receive(trace(slot, trajectory), rng);
}

BeamEchoes MsisModel::trace(const BeamSlot& slot, const VehicleTrajectory& trajectory) const {
  thread_local Workspace work;
  const Ping ping = ping_of(slot, trajectory);
  BeamEchoes beam;
  beam.slot = slot;
  work.profile.reset(sonar_.bins);
  beam.rays_cast = trace_routes(ping, work);
  work.profile.settle();
  beam.truth = truth_of(ping, work.profile, trajectory.at(slot.t_s).pose);
  // The bins from the first to the last that received anything.
  const std::size_t n = work.profile.direct.size();
  std::size_t first = 0, end = n;
  const auto power = [&](std::size_t k) {
    return work.profile.direct[k] + work.profile.multipath[k];
  };
  while (first < n && power(first) == 0.0) ++first;
  while (end > first && power(end - 1) == 0.0) --end;
  beam.first_bin = static_cast<std::uint32_t>(first);
  beam.power.reserve(end - first);
  for (std::size_t k = first; k < end; ++k) beam.power.push_back(power(k));
  return beam;
}

RenderedBeam MsisModel::receive(const BeamEchoes& echoes, Rng& rng) const {
  return receive_beam(receiver_, echoes, rng);
}

MsisReceiver MsisModel::receiver_of(const SonarConfig& sonar) {
  return MsisReceiver(sonar, pattern_norm_of(aperture_rays(sonar), sonar));
}

RenderedBeam receive_beam(const MsisReceiver& receiver, const BeamEchoes& echoes, Rng& rng) {
  thread_local std::vector<double> scratch;
  RenderedBeam beam;
  beam.slot = echoes.slot;
  beam.rays_cast = echoes.rays_cast;
  beam.truth = echoes.truth;
  beam.intensity = receiver.to_intensity(echoes.first_bin, echoes.power, rng, scratch);
  return beam;
}

std::uint32_t MsisModel::trace_routes(const Ping& ping, Workspace& work) const {
  const double max_range_m = max_physical_range_m(sonar_);
  const float c = static_cast<float>(ping.tx.axis.x()), s = static_cast<float>(ping.tx.axis.y());
  primary_rays(ping, work.rays);
  work.routes.clear();
  for (const RayTemplate& ray : rays_) {
    work.routes.push_back({&ray, Eigen::Vector3f::Zero(), rotate_z(ray.cell_azimuth_beam, c, s),
                           rotate_z(ray.cell_elevation_beam, c, s), 0.0, ray.weight});
  }
  auto rays_cast = static_cast<std::uint32_t>(work.rays.size());
  for (int bounce = 0;; ++bounce) {
    scene_.intersect(work.rays, work.hits);  // Embree packets, a bounce's rays together
    work.echoes.clear();
    std::size_t bouncing = 0;  // the routes that go on, moved to the front with their rays
    for (std::size_t i = 0; i < work.routes.size(); ++i) {
      const RayHit& hit = work.hits[i];
      if (!hit.hit) continue;
      Route& route = work.routes[i];
      const Ray& ray = work.rays[i];  // the ray that reached the surface
      route.path_m += hit.distance_m;
      const Eigen::Vector3f hit_point = ray.origin_m + hit.distance_m * ray.direction;
      if (bounce == 0) route.first_hit_m = hit_point;
      work.echoes.push_back(echo_at(route, ray.direction, hit_point, hit, bounce));
      const float specular = scene_.materials()[hit.material_id].specular;
      if (bounce >= sonar_.multipath_bounces || specular <= 0.0f) continue;
      // Specular route: the echo of the next surface comes back the same way, so the mirror's
      // coefficient counts twice.
      Ray next;
      next.t_max_m = static_cast<float>(max_range_m - route.path_m);
      if (next.t_max_m <= 0.0f) continue;
      next.direction = mirror(ray.direction, hit.normal);
      next.origin_m = hit_point + 1e-3f * hit.normal;
      route.route_gain *= static_cast<double>(specular) * specular;
      route.cell_azimuth = mirror(route.cell_azimuth, hit.normal);
      route.cell_elevation = mirror(route.cell_elevation, hit.normal);
      work.rays[bouncing] = next;  // index <= i: rays[i] is not read again
      if (bouncing != i) work.routes[bouncing] = route;
      ++bouncing;
    }
    receiver_.add_echoes(ping, work.echoes, work.profile, work.receiver);
    if (bouncing == 0) return rays_cast;
    work.routes.resize(bouncing);
    work.rays.resize(bouncing);
    rays_cast += static_cast<std::uint32_t>(bouncing);
  }
}

Echo MsisModel::echo_at(const Route& route, const Eigen::Vector3f& d,
                        const Eigen::Vector3f& hit_point_m, const RayHit& hit, int bounce) const {
  const Material& material = scene_.materials()[hit.material_id];
  const double cos_incidence = std::abs(d.dot(hit.normal));
  // Backscatter: strength x cos^n(incidence) toward the source (n = 2: Lambert), varied along
  // the surface by its roughness; over the ray's footprint, of area path^2 x cell /
  // cos(incidence).
  Echo echo;
  echo.first_hit_m = route.first_hit_m;
  echo.path_m = route.path_m;
  echo.extent_m =
      footprint_extent(route.path_m, d, route.cell_azimuth, route.cell_elevation, hit.normal);
  echo.power =
      route.route_gain *
      backscatter_per_area(material.backscatter, cos_incidence, material.incidence_exponent) *
      footprint_area(route.path_m, route.ray->cell_sr, cos_incidence);
  echo.log_gain = roughness_log_gain(hit_point_m);
  echo.multipath = bounce > 0;
  echo.material_id = hit.material_id;
  return echo;
}

BeamTruth MsisModel::truth_of(const Ping& ping, const EchoProfile& echoes,
                              const Pose2& vehicle) const {
  BeamTruth truth;
  truth.vehicle = vehicle;
  truth.bearing_vehicle_rad = ping.bearing_vehicle_rad;
  Ray axis;
  axis.origin_m = ping.tx.position_m;
  axis.direction = direction(ping.tx.axis_azimuth_rad, -sonar_.tilt_deg * kDegToRad);
  axis.t_max_m = static_cast<float>(max_physical_range_m(sonar_));
  const RayHit hit = scene_.intersect(axis);
  if (hit.hit) truth.first_hit_range_m = hit.distance_m;
  // The strongest echo as displayed (after TVG), before speckle and noise.
  double best = 0.0;
  long strongest = -1;
  for (int j = 0; j < sonar_.bins; ++j) {
    const auto k = static_cast<std::size_t>(j);
    const double shown = (echoes.direct[k] + echoes.multipath[k]) * receiver_.tvg(k);
    if (shown > best) {
      best = shown;
      strongest = j;
      truth.strongest_range_m = (j + 1) * sonar_.bin_m;
      truth.strongest_is_multipath = echoes.multipath[k] > echoes.direct[k];
    }
  }
  if (strongest < 0) return truth;
  // The surface whose single echo gave the most to that bin.
  double largest = 0.0;
  for (const EchoProfile::Contribution& c : echoes.contributions) {
    if (c.at(strongest) > largest) {
      largest = c.at(strongest);
      truth.strongest_surface = scene_.materials()[c.material_id].name;
      const Eigen::Vector3d to_source =
          c.first_hit_m.cast<double>() - ping.tx.position_m.cast<double>();
      truth.strongest_bearing_offset_rad = std::remainder(
          std::atan2(to_source.y(), to_source.x()) - ping.tx.axis_azimuth_rad, 2.0 * kPi);
    }
  }
  return truth;
}

}  // namespace msislab::sim
