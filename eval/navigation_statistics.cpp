#include "eval/navigation_statistics.hpp"

#include <Eigen/Dense>
#include <algorithm>
#include <cassert>
#include <cmath>

#include "eval/evaluation.hpp"
#include "geometry/angles.hpp"
#include "geometry/se2.hpp"
#include "stats/sample_statistics.hpp"

namespace msislab {

namespace {

/// Noise sigma from differences whose variance is `factor` sigma^2.
DifferenceNoise noise_of_differences(const std::vector<double>& d, double factor) {
  DifferenceNoise noise;
  noise.count = d.size();
  double mean = 0.0;
  for (const double v : d) mean += v;
  mean /= static_cast<double>(d.size());
  double m2 = 0.0, m4 = 0.0;
  for (const double v : d) {
    const double e2 = (v - mean) * (v - mean);
    m2 += e2;
    m4 += e2 * e2;
  }
  noise.sigma_sd = std::sqrt(m2 / static_cast<double>(d.size() - 1) / factor);
  noise.kurtosis = m4 * static_cast<double>(d.size()) / (m2 * m2);
  const double centre = median(d);
  std::vector<double> deviation;
  deviation.reserve(d.size());
  for (const double v : d) deviation.push_back(std::abs(v - centre));
  noise.sigma_mad = 1.4826 * median(deviation) / std::sqrt(factor);
  return noise;
}

/// 1 / median of the intervals between consecutive time stamps.
template <typename T>
double rate_of(const std::vector<T>& samples) {
  std::vector<double> dt;
  for (std::size_t i = 1; i < samples.size(); ++i)
    dt.push_back(samples[i].t_s - samples[i - 1].t_s);
  return 1.0 / median(dt);
}

}  // namespace

DifferenceNoise difference_noise(const std::vector<double>& values, int order) {
  assert((order == 1 || order == 2) && values.size() >= static_cast<std::size_t>(order) + 2);
  std::vector<double> d;
  for (std::size_t i = order; i < values.size(); ++i) {
    d.push_back(order == 1 ? values[i] - values[i - 1]
                           : values[i] - 2.0 * values[i - 1] + values[i - 2]);
  }
  return noise_of_differences(d, order == 1 ? 2.0 : 6.0);
}

DvlNoiseStatistics dvl_noise_statistics(const std::vector<DvlVelocity>& dvl) {
  DvlNoiseStatistics stats;
  stats.rate_hz = rate_of(dvl);
  // Consecutive samples only: a dropout between two samples doubles the interval.
  std::vector<double> surge, sway;
  std::vector<Eigen::Vector2d> differences;
  for (std::size_t i = 1; i < dvl.size(); ++i) {
    if (dvl[i].t_s - dvl[i - 1].t_s > 1.5 / stats.rate_hz) continue;
    const Eigen::Vector2d d = dvl[i].v_vehicle_mps - dvl[i - 1].v_vehicle_mps;
    surge.push_back(d.x());
    sway.push_back(d.y());
    differences.push_back(d);
  }
  stats.surge_mps = noise_of_differences(surge, 2.0);
  stats.sway_mps = noise_of_differences(sway, 2.0);
  stats.mixture_mps = fit_contaminated_normal(differences);
  return stats;
}

DropoutStatistics dropout_statistics(const std::vector<DvlRow>& rows, double rate_hz) {
  DropoutStatistics stats;
  stats.rows = rows.size();
  std::vector<bool> lost;
  for (std::size_t i = 0; i < rows.size(); ++i) {
    lost.push_back(!rows[i].bottom_lock);
    if (lost.back()) {
      ++stats.dropouts;
      if (i == 0 || rows[i - 1].bottom_lock) ++stats.bursts;
    }
  }
  stats.fraction = static_cast<double>(stats.dropouts) / static_cast<double>(stats.rows);
  if (stats.bursts > 0) stats.mean_burst_rows = double(stats.dropouts) / double(stats.bursts);
  for (const int block : kDispersionBlocks) {
    std::vector<double> counts;
    for (std::size_t b = 0; b + block <= lost.size(); b += block) {
      counts.push_back(static_cast<double>(std::count(
          lost.begin() + static_cast<long>(b), lost.begin() + static_cast<long>(b + block), true)));
    }
    double mean = 0.0, var = 0.0;
    for (const double c : counts) mean += c / static_cast<double>(counts.size());
    for (const double c : counts)
      var += (c - mean) * (c - mean) / static_cast<double>(counts.size() - 1);
    stats.dispersion.push_back(counts.size() > 1 && mean > 0.0 ? var / mean : 0.0);
  }
  if (stats.dropouts > 0 && stats.dropouts < stats.rows) {
    stats.model = fit_gilbert_elliott(lost);
    stats.degraded_mean_s = stats.model.degraded_mean_samples / rate_hz;
  }
  return stats;
}

HeadingNoiseStatistics heading_noise_statistics(const std::vector<HeadingReading>& heading) {
  HeadingNoiseStatistics stats;
  stats.rate_hz = rate_of(heading);
  std::vector<double> unwrapped_deg = {heading.front().yaw_rad * kRadToDeg};
  for (std::size_t i = 1; i < heading.size(); ++i) {
    const double step_rad = normalize_angle(heading[i].yaw_rad - heading[i - 1].yaw_rad);
    unwrapped_deg.push_back(unwrapped_deg.back() + step_rad * kRadToDeg);
  }
  stats.noise_deg = difference_noise(unwrapped_deg, 2);
  constexpr double kRevolution_s = 13.8;
  std::vector<double> turns_deg;
  for (double t = heading.front().t_s; t + kRevolution_s <= heading.back().t_s;
       t += kRevolution_s) {
    turns_deg.push_back(
        std::abs(normalize_angle(nearest_heading(heading, t + kRevolution_s).yaw_rad -
                                 nearest_heading(heading, t).yaw_rad)) *
        kRadToDeg);
  }
  if (!turns_deg.empty()) stats.turn_per_revolution_deg = median(turns_deg);
  return stats;
}

std::optional<CompassComparison> compare_compasses(const std::vector<HeadingReading>& heading,
                                                   const std::vector<DvlRow>& rows) {
  std::vector<double> t_s, yaw_rad, difference_rad;
  for (const DvlRow& row : rows) {
    if (!row.compass_yaw_rad || heading.empty()) continue;
    const double yaw = nearest_heading(heading, row.t_s).yaw_rad;
    t_s.push_back(row.t_s);
    yaw_rad.push_back(yaw);
    difference_rad.push_back(normalize_angle(*row.compass_yaw_rad - yaw));
  }
  if (t_s.size() < 10) return std::nullopt;
  // Unwrap around the circular mean, then difference = offset + a cos(yaw) + b sin(yaw).
  double sum_sin = 0.0, sum_cos = 0.0;
  for (const double d : difference_rad) sum_sin += std::sin(d), sum_cos += std::cos(d);
  const double centre = std::atan2(sum_sin, sum_cos);
  const auto n = static_cast<Eigen::Index>(t_s.size());
  Eigen::MatrixXd A(n, 3);
  Eigen::VectorXd z(n);
  for (Eigen::Index i = 0; i < n; ++i) {
    A.row(i) << 1.0, std::cos(yaw_rad[i]), std::sin(yaw_rad[i]);
    z(i) = (centre + normalize_angle(difference_rad[i] - centre)) * kRadToDeg;
  }
  const Eigen::Vector3d x = A.colPivHouseholderQr().solve(z);
  const Eigen::VectorXd residual = z - A * x;
  CompassComparison c;
  c.offset_deg = x(0);
  c.deviation_amplitude_deg = std::hypot(x(1), x(2));
  c.deviation_cos_deg = x(1);
  c.deviation_sin_deg = x(2);
  c.residual_sd_deg = std::sqrt(residual.squaredNorm() / static_cast<double>(n - 3));
  // Means over whole blocks only: a last block cut short by the log's end (one reading, say)
  // would weigh its few readings' white noise as much as a block's mean and inflate the spread
  // (a 3000 s run in 200 s blocks ended in a block of one reading: spread 0.05-0.48 deg for
  // white noise whose block means spread 0.058 deg). It joins the block before it when it spans
  // less than half a block.
  std::vector<double> block_means;
  std::vector<Eigen::Index> block_counts;
  for (Eigen::Index i = 0; i < n;) {
    double sum = 0.0;
    Eigen::Index j = i;
    for (; j < n && t_s[j] < t_s[i] + kCompassBlock_s; ++j) sum += residual(j);
    if (j == n && !block_means.empty() && t_s[n - 1] - t_s[i] < kCompassBlock_s / 2.0) {
      const auto before = static_cast<double>(block_counts.back());
      block_means.back() =
          (block_means.back() * before + sum) / (before + static_cast<double>(j - i));
      block_counts.back() += j - i;
    } else {
      block_means.push_back(sum / static_cast<double>(j - i));
      block_counts.push_back(j - i);
    }
    i = j;
  }
  double mean = 0.0, var = 0.0;
  for (const double m : block_means) mean += m / static_cast<double>(block_means.size());
  for (const double m : block_means) var += (m - mean) * (m - mean);
  c.block_mean_sd_deg = std::sqrt(var / static_cast<double>(block_means.size() - 1));
  c.random_walk_bound_deg_per_sqrt_s = c.block_mean_sd_deg / std::sqrt((t_s.back() - t_s[0]) / 6.0);
  return c;
}

NavigationStatistics navigation_statistics(const NavigationData& data) {
  NavigationStatistics stats;
  const NavigationLog& nav = data.navigation;
  stats.dvl = dvl_noise_statistics(nav.dvl);
  stats.dropouts = dropout_statistics(data.dvl_rows, rate_of(data.dvl_rows));
  stats.heading = heading_noise_statistics(nav.heading);
  stats.compasses = compare_compasses(nav.heading, data.dvl_rows);
  // The offset needs independent positions: the GPS where there is one, as on the real data.
  const std::vector<PositionFix>& reference = data.gps.empty() ? data.truth : data.gps;
  if (!reference.empty()) {
    stats.heading_offset = heading_offset_statistics(nav, reference, data.p_vehicle_dvl_m, 50.0);
  }
  if (!data.gps.empty()) {
    GpsOptions options;
    if (stats.heading_offset) options.heading_offset_deg = stats.heading_offset->mean_deg;
    stats.gps = gps_statistics(nav, data.gps, data.p_vehicle_dvl_m, options);
  }
  if (!data.truth.empty()) {
    stats.drift = dead_reckoning_drift(nav, data.truth, data.p_vehicle_dvl_m, {});
  }
  if (data.truth_kind == "simulation" && !data.gps.empty()) {
    stats.drift_against_gps = dead_reckoning_drift(nav, data.gps, data.p_vehicle_dvl_m, {});
  }
  return stats;
}

}  // namespace msislab
