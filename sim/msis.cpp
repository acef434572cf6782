#include "sim/msis.hpp"

#include <algorithm>
#include <cmath>

#include "geometry/calibration.hpp"
#include "sim/msis_beam.hpp"
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

MsisModel::MsisModel(const Scene& scene, const SonarConfig& sonar, double vehicle_depth_m)
    : scene_(scene), sonar_(sonar), depth_m_(vehicle_depth_m) {
  const double h_width = sonar.horizontal_beamwidth_deg * kDegToRad;
  const double v_width = sonar.vertical_beamwidth_deg * kDegToRad;
  // Rays at the centres of equal cells spanning +-span beamwidths around the axis, each weighted
  // by the one-way pattern and its cell's share of the aperture.
  const double h_half = h_width * sonar.horizontal_span_beamwidths;
  const double v_half = v_width * sonar.vertical_span_beamwidths;
  const double h_cell = 2.0 * h_half / sonar.rays_horizontal;
  const double v_cell = 2.0 * v_half / sonar.rays_vertical;
  double total = 0.0;
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
      total += ray.weight * ray.weight;
      rays_.push_back(ray);
    }
  }
  // Point scatterers: normalise so the two-way weights sum to 1, so a plane filling the beam at
  // normal incidence returns its backscatter times the loss. Footprints: the weights stay the
  // pattern itself, since sum b^2 x cell solid angle already approximates the beam's integral
  // of b^2 over solid angle, the same for any number of rays.
  pattern_norm_ = sonar.footprint ? 1.0 : std::sqrt(total);
  for (RayTemplate& ray : rays_) ray.weight /= pattern_norm_;
  // Gain + TVG per bin: gain_db + tvg x log10(max(r, 1)).
  for (int j = 0; j < sonar.bins; ++j) {
    const double range_m = (j + 1) * sonar.bin_m;
    const double tvg_db =
        sonar.gain_db + sonar.tvg_db_per_decade * std::log10(std::max(range_m, 1.0));
    tvg_linear_.push_back(std::pow(10.0, tvg_db / 10.0));
  }
  pulse_kernel_ = pulse_kernel(sonar);
  const double span_db = sonar.display_max_db - sonar.display_min_db;
  level_thresholds_.push_back(0.0);  // intensity 0 for any power
  for (int k = 1; k <= 255; ++k) {
    level_thresholds_.push_back(
        std::pow(10.0, (sonar.display_min_db + (k - 0.5) * span_db / 255.0) / 10.0));
  }
}

MsisModel::Head MsisModel::head_at(double t_s, const VehicleTrajectory& trajectory,
                                   double bearing_vehicle_rad) const {
  const Pose2 vehicle = trajectory.at(t_s).pose;
  const Eigen::Vector2d p = vehicle.transform({sonar_.mount.x_m, sonar_.mount.y_m});
  const double azimuth_rad = vehicle.yaw() + bearing_vehicle_rad;
  return {Eigen::Vector3f(static_cast<float>(p.x()), static_cast<float>(p.y()),
                          static_cast<float>(-depth_m_ + sonar_.mount.z_m)),
          azimuth_rad, Eigen::Vector2d(std::cos(azimuth_rad), std::sin(azimuth_rad))};
}

MsisModel::Ping MsisModel::ping_of(const BeamSlot& slot,
                                   const VehicleTrajectory& trajectory) const {
  Ping ping;
  ping.t_s = slot.t_s;
  ping.bearing_vehicle_rad = sonar_bearing_in_vehicle(slot.transducer_angle_rad, sonar_.mount);
  ping.tx = head_at(slot.t_s, trajectory, ping.bearing_vehicle_rad);
  ping.rx_window_s = 2.0 * sonar_.bins * sonar_.bin_m / sonar_.sound_speed_mps;
  ping.rx_last = head_at(slot.t_s + ping.rx_window_s, trajectory, ping.bearing_vehicle_rad);
  return ping;
}

std::vector<Ray> MsisModel::primary_rays(const Ping& ping) const {
  // Template directions (beam frame, axis along x, tilt applied) rotated to the axis azimuth.
  const float c = static_cast<float>(ping.tx.axis.x()), s = static_cast<float>(ping.tx.axis.y());
  std::vector<Ray> rays(rays_.size());
  for (std::size_t i = 0; i < rays_.size(); ++i) {
    rays[i].origin_m = ping.tx.position_m;
    rays[i].direction = rotate_z(rays_[i].direction_beam, c, s);
    rays[i].t_max_m = static_cast<float>(sonar_.bins * sonar_.bin_m);
  }
  return rays;
}

std::vector<Ray> MsisModel::primary_rays(const BeamSlot& slot,
                                         const VehicleTrajectory& trajectory) const {
  return primary_rays(ping_of(slot, trajectory));
}

RenderedBeam MsisModel::render(const BeamSlot& slot, const VehicleTrajectory& trajectory,
                               Rng& rng) const {
  const Ping ping = ping_of(slot, trajectory);
  const std::vector<Ray> rays = primary_rays(ping);
  std::vector<RayHit> hits;
  scene_.intersect(rays, hits);  // Embree packets

  RenderedBeam beam;
  beam.slot = slot;
  beam.rays_cast = static_cast<std::uint32_t>(rays.size());
  Echoes echoes(sonar_.bins);
  for (std::size_t i = 0; i < rays.size(); ++i) {
    if (hits[i].hit) beam.rays_cast += trace_from(rays_[i], rays[i], hits[i], ping, echoes);
  }
  echoes.settle();
  beam.truth = truth_of(ping, echoes, trajectory.at(slot.t_s).pose);
  beam.intensity = to_intensity(echoes, rng);
  return beam;
}

std::uint32_t MsisModel::trace_from(const RayTemplate& ray, Ray r, RayHit hit, const Ping& ping,
                                    Echoes& echoes) const {
  const double max_range_m = sonar_.bins * sonar_.bin_m;
  const Eigen::Vector3f first_hit_m = r.origin_m + hit.distance_m * r.direction;
  // The ray's cell of the aperture as two edge vectors of its direction; a planar mirror keeps
  // the cell's shape, so they are mirrored with the ray.
  const float c = static_cast<float>(ping.tx.axis.x()), s = static_cast<float>(ping.tx.axis.y());
  Eigen::Vector3f cell_azimuth = rotate_z(ray.cell_azimuth_beam, c, s);
  Eigen::Vector3f cell_elevation = rotate_z(ray.cell_elevation_beam, c, s);
  double path_m = hit.distance_m;
  double route_gain = ray.weight;  // transmit pattern x specular factors of both ways
  std::uint32_t rays_cast = 0;
  for (int bounce = 0;; ++bounce) {
    const Material& material = scene_.materials()[hit.material_id];
    const double cos_incidence = std::abs(r.direction.dot(hit.normal));
    const Eigen::Vector3f hit_point = r.origin_m + hit.distance_m * r.direction;
    // Backscatter: strength x cos^n(incidence) toward the source (n = 2: Lambert), varied along
    // the surface by its roughness; over the ray's footprint, of area path^2 x cell /
    // cos(incidence).
    const double backscatter = with_incidence_law(material.backscatter * roughness_gain(hit_point),
                                                  cos_incidence, material.incidence_exponent) *
                               footprint_area(path_m, ray.cell_sr, cos_incidence);
    add_echo(ping, first_hit_m, path_m,
             footprint_extent(path_m, r.direction, cell_azimuth, cell_elevation, hit.normal),
             route_gain * backscatter, bounce > 0, hit.material_id, echoes);
    if (bounce >= sonar_.multipath_bounces || material.specular <= 0.0f) return rays_cast;
    // Specular route: the echo of the next surface comes back the same way, so the mirror's
    // coefficient counts twice.
    route_gain *= static_cast<double>(material.specular) * material.specular;
    r.direction = mirror(r.direction, hit.normal);
    cell_azimuth = mirror(cell_azimuth, hit.normal);
    cell_elevation = mirror(cell_elevation, hit.normal);
    r.origin_m = hit_point + 1e-3f * hit.normal;
    r.t_max_m = static_cast<float>(max_range_m - path_m);
    if (r.t_max_m <= 0.0f) return rays_cast;
    hit = scene_.intersect(r);
    ++rays_cast;
    if (!hit.hit) return rays_cast;
    path_m += hit.distance_m;
  }
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
  return std::min(std::hypot(w_azimuth, w_elevation), kMaxExtent_m);
}

double MsisModel::footprint_area(double path_m, double cell_sr, double cos_incidence) const {
  if (!sonar_.footprint) return 1.0;
  return path_m * path_m * cell_sr / std::max(cos_incidence, kMinFootprintCos);
}

double MsisModel::roughness_gain(const Eigen::Vector3f& point_m) const {
  if (sonar_.roughness_db <= 0.0) return 1.0;
  // Log-normal with mean 1: 10^(sigma_dB g / 10) / E[.], g the unit field.
  const double sigma_ln = sonar_.roughness_db * std::log(10.0) / 10.0;
  return std::exp(sigma_ln * roughness_field(point_m, sonar_.roughness_length_m) -
                  0.5 * sigma_ln * sigma_ln);
}

// add_echo, quantise and to_intensity, the receiving side: sim/msis_receiver.cpp.

BeamTruth MsisModel::truth_of(const Ping& ping, const Echoes& echoes, const Pose2& vehicle) const {
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
    const double shown = (echoes.direct[k] + echoes.multipath[k]) * tvg_linear_[k];
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
  for (const Echoes::Contribution& c : echoes.contributions) {
    if (c.at(strongest) > largest) {
      largest = c.at(strongest);
      truth.strongest_surface = scene_.materials()[c.material_id].name;
    }
  }
  return truth;
}

}  // namespace msislab::sim
