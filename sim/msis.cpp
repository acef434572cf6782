#include "sim/msis.hpp"

#include <algorithm>
#include <cmath>

#include "geometry/calibration.hpp"
#include "sim/sonar_physics.hpp"

namespace msislab::sim {

namespace {
constexpr double kDegToRad = M_PI / 180.0;
/// At grazing incidence a footprint's area and extent grow without bound as 1 / cos; the beam
/// bounds them in fact, so cos(incidence) is taken as at least this.
constexpr double kMinFootprintCos = 0.02;

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

/// strength x cos^n(incidence), the backscatter law per unit area. Lambert's n = 2 multiplies by
/// the cosine twice, in the order the law always had, so its bytes stay the same.
double with_incidence_law(double strength, double cos_incidence, float exponent) {
  if (exponent == 2.0f) return strength * cos_incidence * cos_incidence;
  if (exponent == 1.0f) return strength * cos_incidence;
  return strength * std::pow(cos_incidence, static_cast<double>(exponent));
}

/// Rotation about z by the beam axis azimuth (cos, sin).
Eigen::Vector3f rotate_z(const Eigen::Vector3f& v, float c, float s) {
  return Eigen::Vector3f(c * v.x() - s * v.y(), s * v.x() + c * v.y(), v.z());
}

Eigen::Vector3f mirror(const Eigen::Vector3f& v, const Eigen::Vector3f& normal) {
  return v - 2.0f * v.dot(normal) * normal;
}

}  // namespace

double two_way_loss(double range_m, double absorption_db_per_m) {
  // 10^(-(40 log10 r + 2 alpha r) / 10) = r^-4 exp(-0.2 ln(10) alpha r), without log10 or pow.
  const double r = std::max(range_m, 1.0);
  const double r2 = r * r;
  return std::exp(-0.2 * std::log(10.0) * absorption_db_per_m * range_m) / (r2 * r2);
}

std::vector<BeamSlot> beam_schedule(const SonarConfig& sonar, double t_begin_s, double t_end_s) {
  const double period_s = sonar.revolution_s / sonar.steps_per_revolution;
  const double step_rad = 2.0 * M_PI / sonar.steps_per_revolution;
  std::vector<BeamSlot> slots;
  for (std::uint64_t k = 0;; ++k) {
    const double t_s = t_begin_s + static_cast<double>(k) * period_s;
    if (t_s > t_end_s) break;
    const auto n = static_cast<std::uint64_t>(sonar.steps_per_revolution);
    const std::uint64_t angle_index = (n - k % n) % n;
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
    rays[i].t_max_m = static_cast<float>(sonar_.bins * sonar_.bin_m);
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
  Ray last;  ///< the ray that reached the surface
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
  std::vector<double> echo_scratch;
};

RenderedBeam MsisModel::render(const BeamSlot& slot, const VehicleTrajectory& trajectory,
                               Rng& rng) const {
  thread_local Workspace work;
  const Ping ping = ping_of(slot, trajectory);
  RenderedBeam beam;
  beam.slot = slot;
  work.profile.reset(sonar_.bins);
  beam.rays_cast = trace_routes(ping, work);
  work.profile.settle();
  beam.truth = truth_of(ping, work.profile, trajectory.at(slot.t_s).pose);
  beam.intensity = receiver_.to_intensity(work.profile, rng, work.echo_scratch);
  return beam;
}

std::uint32_t MsisModel::trace_routes(const Ping& ping, Workspace& work) const {
  const double max_range_m = sonar_.bins * sonar_.bin_m;
  const float c = static_cast<float>(ping.tx.axis.x()), s = static_cast<float>(ping.tx.axis.y());
  primary_rays(ping, work.rays);
  work.routes.clear();
  for (const RayTemplate& ray : rays_) {
    work.routes.push_back({&ray, Ray{}, Eigen::Vector3f::Zero(),
                           rotate_z(ray.cell_azimuth_beam, c, s),
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
      route.last = work.rays[i];
      route.path_m += hit.distance_m;
      const Eigen::Vector3f hit_point = route.last.origin_m + hit.distance_m * route.last.direction;
      if (bounce == 0) route.first_hit_m = hit_point;
      work.echoes.push_back(echo_at(route, hit, bounce));
      const float specular = scene_.materials()[hit.material_id].specular;
      if (bounce >= sonar_.multipath_bounces || specular <= 0.0f) continue;
      // Specular route: the echo of the next surface comes back the same way, so the mirror's
      // coefficient counts twice.
      route.route_gain *= static_cast<double>(specular) * specular;
      route.last.direction = mirror(route.last.direction, hit.normal);
      route.cell_azimuth = mirror(route.cell_azimuth, hit.normal);
      route.cell_elevation = mirror(route.cell_elevation, hit.normal);
      route.last.origin_m = hit_point + 1e-3f * hit.normal;
      route.last.t_max_m = static_cast<float>(max_range_m - route.path_m);
      if (route.last.t_max_m <= 0.0f) continue;
      work.rays[bouncing] = route.last;  // index <= i: rays[i] was read above
      work.routes[bouncing++] = route;
    }
    receiver_.add_echoes(ping, work.echoes, work.profile, work.receiver);
    if (bouncing == 0) return rays_cast;
    work.routes.resize(bouncing);
    work.rays.resize(bouncing);
    rays_cast += static_cast<std::uint32_t>(bouncing);
  }
}

Echo MsisModel::echo_at(const Route& route, const RayHit& hit, int bounce) const {
  const Material& material = scene_.materials()[hit.material_id];
  const Eigen::Vector3f& d = route.last.direction;
  const double cos_incidence = std::abs(d.dot(hit.normal));
  const Eigen::Vector3f hit_point = route.last.origin_m + hit.distance_m * d;
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
      with_incidence_law(material.backscatter, cos_incidence, material.incidence_exponent) *
      footprint_area(route.path_m, route.ray->cell_sr, cos_incidence);
  echo.log_gain = roughness_log_gain(hit_point);
  echo.multipath = bounce > 0;
  echo.material_id = hit.material_id;
  return echo;
}

double MsisModel::footprint_extent(double path_m, const Eigen::Vector3f& direction,
                                   const Eigen::Vector3f& cell_azimuth,
                                   const Eigen::Vector3f& cell_elevation,
                                   const Eigen::Vector3f& normal) const {
  if (!sonar_.footprint) return 0.0;
  // A surface at distance t along d, normal n: t(d) = const / (d . n), so a change dd of the
  // direction moves the hit by dt = -t (dd . n) / (d . n). Over the cell's two edges the ranges
  // cover two boxes; their sum has the variance of a box of width sqrt(w_a^2 + w_e^2).
  constexpr double kMaxExtent_m = 10.0;
  const double cos_incidence =
      std::max(std::abs(static_cast<double>(direction.dot(normal))), kMinFootprintCos);
  const double w_azimuth = path_m * std::abs(cell_azimuth.dot(normal)) / cos_incidence;
  const double w_elevation = path_m * std::abs(cell_elevation.dot(normal)) / cos_incidence;
  // Both widths are bounded (path <= the sonar's range, cos >= kMinFootprintCos): no overflow.
  return std::min(std::sqrt(w_azimuth * w_azimuth + w_elevation * w_elevation), kMaxExtent_m);
}

double MsisModel::footprint_area(double path_m, double cell_sr, double cos_incidence) const {
  if (!sonar_.footprint) return 1.0;
  return path_m * path_m * cell_sr / std::max(cos_incidence, kMinFootprintCos);
}

double MsisModel::roughness_log_gain(const Eigen::Vector3f& point_m) const {
  if (sonar_.roughness_db <= 0.0) return 0.0;
  // Log-normal with mean 1: 10^(sigma_dB g / 10) / E[.], g the unit field.
  const double sigma_ln = sonar_.roughness_db * std::log(10.0) / 10.0;
  return sigma_ln * roughness_field(point_m, sonar_.roughness_length_m) - 0.5 * sigma_ln * sigma_ln;
}

BeamTruth MsisModel::truth_of(const Ping& ping, const EchoProfile& echoes,
                              const Pose2& vehicle) const {
  BeamTruth truth;
  truth.vehicle = vehicle;
  truth.bearing_vehicle_rad = ping.bearing_vehicle_rad;
  Ray axis;
  axis.origin_m = ping.tx.position_m;
  axis.direction = direction(ping.tx.axis_azimuth_rad, -sonar_.tilt_deg * kDegToRad);
  axis.t_max_m = static_cast<float>(sonar_.bins * sonar_.bin_m);
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
    }
  }
  return truth;
}

}  // namespace msislab::sim
