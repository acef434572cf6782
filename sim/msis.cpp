#include "sim/msis.hpp"

#include <algorithm>
#include <cmath>

#include "slam/calibration.hpp"

namespace msislab::sim {

namespace {
constexpr double kDegToRad = M_PI / 180.0;
const double kLn2 = std::log(2.0);

/// One-way beam pattern: Gaussian with -3 dB two-way at +-width/2, so one-way
/// b(a) = exp(-2 ln2 (2a/width)^2) and b^2 is the two-way pattern.
double one_way_pattern(double azimuth_rad, double elevation_rad, double h_width_rad,
                       double v_width_rad) {
  const double h = 2.0 * azimuth_rad / h_width_rad;
  const double v = 2.0 * elevation_rad / v_width_rad;
  return std::exp(-2.0 * kLn2 * (h * h + v * v));
}

Eigen::Vector3f direction(double azimuth_rad, double elevation_rad) {
  return Eigen::Vector3f(static_cast<float>(std::cos(elevation_rad) * std::cos(azimuth_rad)),
                         static_cast<float>(std::cos(elevation_rad) * std::sin(azimuth_rad)),
                         static_cast<float>(std::sin(elevation_rad)));
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

struct MsisModel::Head {
  Eigen::Vector3f position_m;
  double axis_azimuth_rad = 0.0;                    ///< world azimuth of the beam axis
  Eigen::Vector2d axis = Eigen::Vector2d::UnitX();  ///< [cos, sin] of that azimuth
};

/// One beam's transmission: the head at transmit and at the latest possible receive time (the
/// echo from maximum range); receive poses in between are interpolated (tens of ms, a few cm).
struct MsisModel::Ping {
  double t_s = 0.0;
  double bearing_vehicle_rad = 0.0;
  Head tx;
  Head rx_last;
  double rx_window_s = 0.0;
};

struct MsisModel::Echoes {
  explicit Echoes(int bins)
      : direct(bins, 0.0), multipath(bins, 0.0), largest(bins, 0.0), largest_material(bins, 0) {}
  std::vector<double> direct;                   ///< power per bin by direct backscatter
  std::vector<double> multipath;                ///< power per bin by a specular route
  std::vector<double> largest;                  ///< the largest single contribution to each bin
  std::vector<std::uint32_t> largest_material;  ///< the surface that returned it
};

MsisModel::MsisModel(const Scene& scene, const SonarConfig& sonar, double vehicle_depth_m)
    : scene_(scene), sonar_(sonar), depth_m_(vehicle_depth_m) {
  const double h_width = sonar.horizontal_beamwidth_deg * kDegToRad;
  const double v_width = sonar.vertical_beamwidth_deg * kDegToRad;
  // Rays at the centres of equal cells spanning +-one beamwidth (the two-way pattern is 1/16
  // there), each weighted by the one-way pattern and its cell's share of the aperture.
  double total = 0.0;
  for (int i = 0; i < sonar.rays_horizontal; ++i) {
    for (int j = 0; j < sonar.rays_vertical; ++j) {
      RayTemplate ray;
      ray.azimuth_rad = h_width * (-1.0 + (2.0 * i + 1.0) / sonar.rays_horizontal);
      ray.elevation_rad = v_width * (-1.0 + (2.0 * j + 1.0) / sonar.rays_vertical);
      ray.weight = one_way_pattern(ray.azimuth_rad, ray.elevation_rad, h_width, v_width);
      ray.direction_beam =
          direction(ray.azimuth_rad, ray.elevation_rad - sonar.tilt_deg * kDegToRad);
      total += ray.weight * ray.weight;
      rays_.push_back(ray);
    }
  }
  // Normalise so the two-way weights sum to 1: a plane filling the beam at normal incidence
  // returns its backscatter times the loss.
  pattern_norm_ = std::sqrt(total);
  for (RayTemplate& ray : rays_) ray.weight /= pattern_norm_;
  // Gain + TVG per bin: gain_db + tvg x log10(max(r, 1)).
  for (int j = 0; j < sonar.bins; ++j) {
    const double range_m = (j + 1) * sonar.bin_m;
    const double tvg_db =
        sonar.gain_db + sonar.tvg_db_per_decade * std::log10(std::max(range_m, 1.0));
    tvg_linear_.push_back(std::pow(10.0, tvg_db / 10.0));
  }
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
    const Eigen::Vector3f& d = rays_[i].direction_beam;
    rays[i].origin_m = ping.tx.position_m;
    rays[i].direction = Eigen::Vector3f(c * d.x() - s * d.y(), s * d.x() + c * d.y(), d.z());
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
  beam.truth = truth_of(ping, echoes, trajectory.at(slot.t_s).pose);
  beam.intensity = to_intensity(echoes, rng);
  return beam;
}

std::uint32_t MsisModel::trace_from(const RayTemplate& ray, Ray r, RayHit hit, const Ping& ping,
                                    Echoes& echoes) const {
  const double max_range_m = sonar_.bins * sonar_.bin_m;
  const Eigen::Vector3f first_hit_m = r.origin_m + hit.distance_m * r.direction;
  double path_m = hit.distance_m;
  double route_gain = ray.weight;  // transmit pattern x specular factors of both ways
  std::uint32_t rays_cast = 0;
  for (int bounce = 0;; ++bounce) {
    const Material& material = scene_.materials()[hit.material_id];
    const double cos_incidence = std::abs(r.direction.dot(hit.normal));
    // Lambert-like backscatter: strength x cos^2(incidence) toward the source.
    add_echo(ping, first_hit_m, path_m,
             route_gain * material.backscatter * cos_incidence * cos_incidence, bounce > 0,
             hit.material_id, echoes);
    if (bounce >= sonar_.multipath_bounces || material.specular <= 0.0f) return rays_cast;
    // Specular route: the echo of the next surface comes back the same way, so the mirror's
    // coefficient counts twice.
    route_gain *= static_cast<double>(material.specular) * material.specular;
    const Eigen::Vector3f hit_point = r.origin_m + hit.distance_m * r.direction;
    r.direction = r.direction - 2.0f * r.direction.dot(hit.normal) * hit.normal;
    r.origin_m = hit_point + 1e-3f * hit.normal;
    r.t_max_m = static_cast<float>(max_range_m - path_m);
    if (r.t_max_m <= 0.0f) return rays_cast;
    hit = scene_.intersect(r);
    ++rays_cast;
    if (!hit.hit) return rays_cast;
    path_m += hit.distance_m;
  }
}

void MsisModel::add_echo(const Ping& ping, const Eigen::Vector3f& first_hit_m, double path_m,
                         double power, bool multipath, std::uint32_t material_id,
                         Echoes& echoes) const {
  // Received at t + 2 path / c: the last leg of the return runs from the first surface on the
  // route to where the head is then, and the receive pattern is taken there.
  const double w = std::clamp(2.0 * path_m / sonar_.sound_speed_mps / ping.rx_window_s, 0.0, 1.0);
  const Eigen::Vector3f rx_m =
      ping.tx.position_m + static_cast<float>(w) * (ping.rx_last.position_m - ping.tx.position_m);
  const Eigen::Vector2d rx_axis =
      (ping.tx.axis + w * (ping.rx_last.axis - ping.tx.axis)).normalized();
  const Eigen::Vector3f to_hit = first_hit_m - rx_m;
  const double rx_leg_m = to_hit.norm();
  const double tx_leg_m = (first_hit_m - ping.tx.position_m).norm();
  const double range_m = (2.0 * path_m - tx_leg_m + rx_leg_m) / 2.0;
  if (range_m < sonar_.min_range_m) return;
  const long bin = static_cast<long>(range_m / sonar_.bin_m + 0.5) - 1;  // range_m > 0
  if (bin < 0 || bin >= sonar_.bins) return;
  // The return direction in the receive head's frame: forward along the axis, left across it.
  const double forward = rx_axis.x() * to_hit.x() + rx_axis.y() * to_hit.y();
  const double left = rx_axis.x() * to_hit.y() - rx_axis.y() * to_hit.x();
  const double azimuth = std::atan2(left, forward);
  const double elevation =
      std::asin(std::clamp(to_hit.z() / rx_leg_m, -1.0, 1.0)) + sonar_.tilt_deg * kDegToRad;
  const double rx_pattern =
      one_way_pattern(azimuth, elevation, sonar_.horizontal_beamwidth_deg * kDegToRad,
                      sonar_.vertical_beamwidth_deg * kDegToRad) /
      pattern_norm_;
  const double received = power * rx_pattern * two_way_loss(path_m, sonar_.absorption_db_per_m);
  const auto k = static_cast<std::size_t>(bin);
  (multipath ? echoes.multipath : echoes.direct)[k] += received;
  if (received > echoes.largest[k]) {
    echoes.largest[k] = received;
    echoes.largest_material[k] = material_id;
  }
}

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
  for (int j = 0; j < sonar_.bins; ++j) {
    const auto k = static_cast<std::size_t>(j);
    const double shown = (echoes.direct[k] + echoes.multipath[k]) * tvg_linear_[k];
    if (shown > best) {
      best = shown;
      truth.strongest_range_m = (j + 1) * sonar_.bin_m;
      truth.strongest_is_multipath = echoes.multipath[k] > echoes.direct[k];
      truth.strongest_surface = scene_.materials()[echoes.largest_material[k]].name;
    }
  }
  return truth;
}

std::uint8_t MsisModel::quantise(double shown) const {
  // Branchless binary search for the last boundary <= shown (entry 0 is below every power).
  std::size_t at = 0;
  for (std::size_t half = 128; half > 0; half /= 2) {
    at += static_cast<std::size_t>(level_thresholds_[at + half] <= shown) * half;
  }
  return static_cast<std::uint8_t>(at);
}

std::vector<std::uint8_t> MsisModel::to_intensity(const Echoes& echoes, Rng& rng) const {
  static const ExponentialTable exponential;
  const double kMaxExponential = ExponentialTable::max();
  const double noise_power = std::pow(10.0, sonar_.noise_level_db / 10.0);
  std::vector<std::uint8_t> intensity(static_cast<std::size_t>(sonar_.bins));
  for (std::size_t k = 0; k < intensity.size(); ++k) {
    // Rayleigh amplitude speckle = exponential power; background noise likewise.
    double power = echoes.direct[k] + echoes.multipath[k];
    // No echo and even the largest noise draw stays under intensity 1: 0, no draw needed.
    if (power == 0.0 && noise_power * kMaxExponential * tvg_linear_[k] < level_thresholds_[1]) {
      continue;
    }
    if (sonar_.speckle && power > 0.0) power *= exponential(rng);
    power += noise_power * exponential(rng);
    // intensity = round(255 (10 log10(power x tvg) - min_db) / span_db), clamped to 0..255:
    // the number of quantisation boundaries the shown power reaches.
    intensity[k] = quantise(power * tvg_linear_[k]);
  }
  return intensity;
}

}  // namespace msislab::sim
