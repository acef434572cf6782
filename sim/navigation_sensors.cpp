#include "sim/navigation_sensors.hpp"

#include <cmath>
#include <random>
#include <stdexcept>
#include <string>

#include "geometry/angles.hpp"
#include "geometry/calibration.hpp"
#include "sim/random.hpp"
#include "sim/scenario.hpp"

namespace msislab::sim {

namespace {

/// Sample times t0 + k / rate over the trajectory's span.
std::vector<double> sample_times(const VehicleTrajectory& truth, double rate_hz) {
  std::vector<double> times;
  for (std::uint64_t k = 0;; ++k) {
    const double t_s = truth.start_s() + static_cast<double>(k) / rate_hz;
    if (t_s > truth.end_s()) break;
    times.push_back(t_s);
  }
  return times;
}

double altitude_below(const Scene& scene, const Pose2& pose, double depth_m, double max_m) {
  Ray down;
  down.origin_m = Eigen::Vector3f(static_cast<float>(pose.x()), static_cast<float>(pose.y()),
                                  static_cast<float>(-depth_m));
  down.direction = -Eigen::Vector3f::UnitZ();
  down.t_max_m = static_cast<float>(max_m);
  const RayHit hit = scene.intersect(down);
  return hit.hit ? hit.distance_m : 0.0;
}
}  // namespace

std::vector<double> dvl_altitudes(const VehicleTrajectory& truth, const DvlConfig& dvl,
                                  const Scene& scene, double depth_m) {
  std::vector<double> altitudes_m;
  for (const double t_s : sample_times(truth, dvl.rate_hz)) {
    altitudes_m.push_back(altitude_below(scene, truth.at(t_s).pose, depth_m, dvl.max_altitude_m));
  }
  return altitudes_m;
}

std::vector<DvlSample> simulate_dvl(const VehicleTrajectory& truth, const DvlConfig& dvl,
                                    const Scene& scene, double depth_m, std::uint64_t seed) {
  return simulate_dvl(truth, dvl, dvl_altitudes(truth, dvl, scene, depth_m), seed);
}

std::vector<DvlSample> simulate_dvl(const VehicleTrajectory& truth, const DvlConfig& dvl,
                                    const std::vector<double>& altitudes_m, std::uint64_t seed) {
  const std::vector<double> times = sample_times(truth, dvl.rate_hz);
  if (altitudes_m.size() != times.size()) {
    throw std::invalid_argument("simulate_dvl: " + std::to_string(altitudes_m.size()) +
                                " altitudes for " + std::to_string(times.size()) + " samples");
  }
  Rng rng = make_rng(seed, RandomStream::kDvl, 0);
  std::normal_distribution<double> n01(0.0, 1.0);
  std::uniform_real_distribution<double> u01(0.0, 1.0);
  const Eigen::Matrix2d R_dvl_vehicle = R_vehicle_dvl(dvl.mount).transpose();
  // The clear/degraded chain per sample of dt: leave a state of mean duration T with
  // probability 1 - exp(-dt / T); the clear periods last T_d (1 - f) / f for a degraded fraction f.
  const double dt_s = 1.0 / dvl.rate_hz;
  const double leave_degraded =
      dvl.degraded_fraction > 0.0 ? -std::expm1(-dt_s / dvl.degraded_duration_s) : 1.0;
  const double enter_degraded =
      dvl.degraded_fraction > 0.0
          ? -std::expm1(-dt_s * dvl.degraded_fraction /
                        ((1.0 - dvl.degraded_fraction) * dvl.degraded_duration_s))
          : 0.0;
  bool degraded = u01(rng) < dvl.degraded_fraction;
  std::vector<DvlSample> samples;
  for (std::size_t i = 0; i < times.size(); ++i) {
    const double t_s = times[i];
    const VehicleState s = truth.at(t_s);
    DvlSample sample;
    sample.t_s = t_s;
    sample.altitude_m = altitudes_m[i];
    // Velocity of the DVL's mount point: v + r x p, in the vehicle frame, then the DVL frame.
    const Eigen::Vector2d v_vehicle(s.surge_mps - s.yaw_rate_radps * dvl.mount.y_m,
                                    s.sway_mps + s.yaw_rate_radps * dvl.mount.x_m);
    // A fixed number of draws per sample, whatever the outcome.
    const double u_dropout = u01(rng), u_outlier = u01(rng), u_state = u01(rng);
    const Eigen::Vector2d noise = draw_y_then_x([&] { return n01(rng); });
    const double p_dropout = degraded ? dvl.degraded_dropout_probability : dvl.dropout_probability;
    const double sigma_mps =
        u_outlier < dvl.outlier_probability ? dvl.outlier_sigma_mps : dvl.noise_sigma_mps;
    sample.bottom_lock = u_dropout >= p_dropout && sample.altitude_m > 0.0;
    if (sample.bottom_lock) {
      sample.v_dvl_mps =
          dvl.scale_factor * (R_dvl_vehicle * v_vehicle) + dvl.bias_mps + sigma_mps * noise;
    }
    degraded = degraded ? u_state >= leave_degraded : u_state < enter_degraded;
    samples.push_back(sample);
  }
  return samples;
}

std::vector<MruSample> simulate_mru(const VehicleTrajectory& truth, const MruConfig& mru,
                                    std::uint64_t seed) {
  Rng rng = make_rng(seed, RandomStream::kMru, 0);
  std::normal_distribution<double> n01(0.0, 1.0);
  double bias_deg = mru.bias_initial_deg;
  const double dt_s = 1.0 / mru.rate_hz;
  std::vector<MruSample> samples;
  for (const double t_s : sample_times(truth, mru.rate_hz)) {
    const double true_yaw_rad = truth.at(t_s).pose.yaw();
    const double deviation_deg = mru.deviation_cos_deg * std::cos(true_yaw_rad) +
                                 mru.deviation_sin_deg * std::sin(true_yaw_rad);
    const double error_deg = bias_deg + deviation_deg + mru.heading_noise_deg * n01(rng);
    const double yaw_rad = true_yaw_rad + error_deg * kDegToRad;
    samples.push_back({t_s, mru_yaw_from_vehicle(yaw_rad, mru.mount)});
    bias_deg += mru.bias_random_walk_deg_per_sqrt_s * std::sqrt(dt_s) * n01(rng);
  }
  return samples;
}

Eigen::Vector2d drag_buoy(const Eigen::Vector2d& p_buoy_m, const Eigen::Vector2d& p_vehicle_m,
                          double tether_m) {
  const Eigen::Vector2d away = p_buoy_m - p_vehicle_m;
  const double distance_m = away.norm();
  if (distance_m <= tether_m) return p_buoy_m;
  return p_vehicle_m + away * (tether_m / distance_m);
}

std::vector<GpsFix> simulate_gps(const VehicleTrajectory& truth, const GpsConfig& gps,
                                 std::uint64_t seed) {
  std::vector<GpsFix> fixes;
  if (!gps.enabled) return fixes;
  Rng rng = make_rng(seed, RandomStream::kGps, 0);
  std::normal_distribution<double> n01(0.0, 1.0);
  // Gauss-Markov error e' = phi e + sigma sqrt(1 - phi^2) n, phi = exp(-dt / tau), stationary.
  const double phi =
      gps.correlated_sigma_m > 0.0 ? std::exp(-1.0 / (gps.rate_hz * gps.correlation_time_s)) : 0.0;
  Eigen::Vector2d e_m = gps.correlated_sigma_m * draw_y_then_x([&] { return n01(rng); });
  // The buoy starts above the vehicle and is dragged through every truth sample.
  const std::vector<VehicleState>& states = truth.samples();
  Eigen::Vector2d p_buoy_m = states.front().pose.translation();
  std::size_t next = 0;
  for (const double t_s : sample_times(truth, gps.rate_hz)) {
    for (; next < states.size() && states[next].t_s <= t_s; ++next) {
      p_buoy_m = drag_buoy(p_buoy_m, states[next].pose.translation(), gps.tether_length_m);
    }
    p_buoy_m = drag_buoy(p_buoy_m, truth.at(t_s).pose.translation(), gps.tether_length_m);
    const Eigen::Vector2d white = draw_y_then_x([&] { return n01(rng); });
    fixes.push_back({t_s, p_buoy_m + e_m + gps.noise_sigma_m * white});
    const Eigen::Vector2d n = draw_y_then_x([&] { return n01(rng); });
    e_m = phi * e_m + gps.correlated_sigma_m * std::sqrt(1.0 - phi * phi) * n;
  }
  return fixes;
}

NavigationNoise navigation_noise_of(const Scenario& scenario) {
  const DvlConfig& dvl = scenario.dvl;
  const MruConfig& mru = scenario.mru;
  NavigationNoise noise;
  noise.dvl_sigma_mps =
      std::sqrt((1.0 - dvl.outlier_probability) * dvl.noise_sigma_mps * dvl.noise_sigma_mps +
                dvl.outlier_probability * dvl.outlier_sigma_mps * dvl.outlier_sigma_mps);
  noise.heading_sigma_deg = mru.heading_noise_deg;
  noise.heading_bias_walk_deg_per_sqrt_s = mru.bias_random_walk_deg_per_sqrt_s;
  noise.heading_bias_sigma_deg = std::abs(mru.bias_initial_deg);
  const double stated_scale = calibration_of(scenario).dvl.scale_factor;
  noise.dvl_scale_sigma = std::abs(dvl.scale_factor / stated_scale - 1.0);
  return noise;
}

}  // namespace msislab::sim
