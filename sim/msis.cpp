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
  const double r = std::max(range_m, 1.0);
  return std::pow(10.0, -(40.0 * std::log10(r) + 2.0 * absorption_db_per_m * range_m) / 10.0);
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
  double axis_azimuth_rad = 0.0;  ///< world azimuth of the beam axis
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
  std::vector<double> direct;     ///< power per bin by direct backscatter
  std::vector<double> multipath;  ///< power per bin by a specular route
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
      total += ray.weight * ray.weight;
      rays_.push_back(ray);
    }
  }
  // Normalise so the two-way weights sum to 1: a plane filling the beam at normal incidence
  // returns its backscatter times the loss.
  pattern_norm_ = std::sqrt(total);
  for (RayTemplate& ray : rays_) ray.weight /= pattern_norm_;
}

MsisModel::Head MsisModel::head_at(double t_s, const VehicleTrajectory& trajectory,
                                   double bearing_vehicle_rad) const {
  const Pose2 vehicle = trajectory.at(t_s).pose;
  const Eigen::Vector2d p = vehicle.transform({sonar_.mount.x_m, sonar_.mount.y_m});
  return {Eigen::Vector3f(static_cast<float>(p.x()), static_cast<float>(p.y()),
                          static_cast<float>(-depth_m_ + sonar_.mount.z_m)),
          vehicle.yaw() + bearing_vehicle_rad};
}

RenderedBeam MsisModel::render(const BeamSlot& slot, const VehicleTrajectory& trajectory,
                               std::mt19937_64& rng) const {
  Ping ping;
  ping.t_s = slot.t_s;
  ping.bearing_vehicle_rad = sonar_bearing_in_vehicle(slot.transducer_angle_rad, sonar_.mount);
  ping.tx = head_at(slot.t_s, trajectory, ping.bearing_vehicle_rad);
  ping.rx_window_s = 2.0 * sonar_.bins * sonar_.bin_m / sonar_.sound_speed_mps;
  ping.rx_last = head_at(slot.t_s + ping.rx_window_s, trajectory, ping.bearing_vehicle_rad);

  Echoes echoes{std::vector<double>(sonar_.bins, 0.0), std::vector<double>(sonar_.bins, 0.0)};
  for (const RayTemplate& ray : rays_) trace_ray(ray, ping, echoes);

  RenderedBeam beam;
  beam.slot = slot;
  beam.truth = truth_of(ping, echoes, trajectory.at(slot.t_s).pose);
  beam.intensity = to_intensity(echoes, rng);
  return beam;
}

void MsisModel::trace_ray(const RayTemplate& ray, const Ping& ping, Echoes& echoes) const {
  const double max_range_m = sonar_.bins * sonar_.bin_m;
  Ray r;
  r.origin_m = ping.tx.position_m;
  r.direction = direction(ping.tx.axis_azimuth_rad + ray.azimuth_rad,
                          ray.elevation_rad - sonar_.tilt_deg * kDegToRad);
  r.t_max_m = static_cast<float>(max_range_m);
  RayHit hit = scene_.intersect(r);
  if (!hit.hit) return;
  const Eigen::Vector3f first_hit_m = r.origin_m + hit.distance_m * r.direction;
  double path_m = hit.distance_m;
  double route_gain = ray.weight;  // transmit pattern x specular factors of both ways
  for (int bounce = 0;; ++bounce) {
    const Material& material = scene_.materials()[hit.material_id];
    const double cos_incidence = std::abs(r.direction.dot(hit.normal));
    // Lambert-like backscatter: strength x cos^2(incidence) toward the source.
    add_echo(ping, first_hit_m, path_m,
             route_gain * material.backscatter * cos_incidence * cos_incidence, bounce > 0, echoes);
    if (bounce >= sonar_.multipath_bounces || material.specular <= 0.0f) return;
    // Specular route: the echo of the next surface comes back the same way, so the mirror's
    // coefficient counts twice.
    route_gain *= static_cast<double>(material.specular) * material.specular;
    const Eigen::Vector3f hit_point = r.origin_m + hit.distance_m * r.direction;
    r.direction = r.direction - 2.0f * r.direction.dot(hit.normal) * hit.normal;
    r.origin_m = hit_point + 1e-3f * hit.normal;
    r.t_max_m = static_cast<float>(max_range_m - path_m);
    if (r.t_max_m <= 0.0f) return;
    hit = scene_.intersect(r);
    if (!hit.hit) return;
    path_m += hit.distance_m;
  }
}

void MsisModel::add_echo(const Ping& ping, const Eigen::Vector3f& first_hit_m, double path_m,
                         double power, bool multipath, Echoes& echoes) const {
  // Received at t + 2 path / c: the last leg of the return runs from the first surface on the
  // route to where the head is then, and the receive pattern is taken there.
  const double w = std::clamp(2.0 * path_m / sonar_.sound_speed_mps / ping.rx_window_s, 0.0, 1.0);
  const Eigen::Vector3f rx_m =
      ping.tx.position_m + static_cast<float>(w) * (ping.rx_last.position_m - ping.tx.position_m);
  const double rx_azimuth_rad =
      ping.tx.axis_azimuth_rad +
      w * normalize_angle(ping.rx_last.axis_azimuth_rad - ping.tx.axis_azimuth_rad);
  const Eigen::Vector3f to_hit = first_hit_m - rx_m;
  const double rx_leg_m = to_hit.norm();
  const double tx_leg_m = (first_hit_m - ping.tx.position_m).norm();
  const double range_m = (2.0 * path_m - tx_leg_m + rx_leg_m) / 2.0;
  if (range_m < sonar_.min_range_m) return;
  const long bin = std::lround(range_m / sonar_.bin_m) - 1;
  if (bin < 0 || bin >= sonar_.bins) return;
  const double azimuth = normalize_angle(std::atan2(to_hit.y(), to_hit.x()) - rx_azimuth_rad);
  const double elevation =
      std::asin(std::clamp(to_hit.z() / rx_leg_m, -1.0, 1.0)) + sonar_.tilt_deg * kDegToRad;
  const double rx_pattern =
      one_way_pattern(azimuth, elevation, sonar_.horizontal_beamwidth_deg * kDegToRad,
                      sonar_.vertical_beamwidth_deg * kDegToRad) /
      pattern_norm_;
  const double received = power * rx_pattern * two_way_loss(path_m, sonar_.absorption_db_per_m);
  (multipath ? echoes.multipath : echoes.direct)[static_cast<std::size_t>(bin)] += received;
}

double MsisModel::tvg_db(double range_m) const {
  return sonar_.gain_db + sonar_.tvg_db_per_decade * std::log10(std::max(range_m, 1.0));
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
    const double range_m = (j + 1) * sonar_.bin_m;
    const double shown =
        (echoes.direct[k] + echoes.multipath[k]) * std::pow(10.0, tvg_db(range_m) / 10.0);
    if (shown > best) {
      best = shown;
      truth.strongest_range_m = range_m;
      truth.strongest_is_multipath = echoes.multipath[k] > echoes.direct[k];
    }
  }
  return truth;
}

std::vector<std::uint8_t> MsisModel::to_intensity(const Echoes& echoes,
                                                  std::mt19937_64& rng) const {
  std::exponential_distribution<double> exponential(1.0);
  const double noise_power = std::pow(10.0, sonar_.noise_level_db / 10.0);
  const double span_db = sonar_.display_max_db - sonar_.display_min_db;
  std::vector<std::uint8_t> intensity(static_cast<std::size_t>(sonar_.bins));
  for (int j = 0; j < sonar_.bins; ++j) {
    const auto k = static_cast<std::size_t>(j);
    // Rayleigh amplitude speckle = exponential power; background noise likewise.
    double power = echoes.direct[k] + echoes.multipath[k];
    if (sonar_.speckle) power *= exponential(rng);
    power += noise_power * exponential(rng);
    const double level_db = 10.0 * std::log10(power) + tvg_db((j + 1) * sonar_.bin_m);
    const double scaled = 255.0 * (level_db - sonar_.display_min_db) / span_db;
    intensity[k] = static_cast<std::uint8_t>(std::clamp(std::lround(scaled), 0L, 255L));
  }
  return intensity;
}

}  // namespace msislab::sim
