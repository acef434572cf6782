// The receiving side of MsisModel (docs/simulator.md): each echo laid over the range bins with
// the receive pattern and the transmission loss, then the profile to intensities with speckle,
// the pulse's spread, noise and quantisation.
#include <algorithm>
#include <cmath>

#include "sim/msis.hpp"
#include "sim/msis_beam.hpp"
#include "sim/sonar_physics.hpp"

namespace msislab::sim {

namespace {
constexpr double kDegToRad = M_PI / 180.0;
}  // namespace

void MsisModel::add_echo(const Ping& ping, const Eigen::Vector3f& first_hit_m, double path_m,
                         double extent_m, double power, bool multipath, std::uint32_t material_id,
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
  // The return direction in the receive head's frame: forward along the axis, left across it.
  const double forward = rx_axis.x() * to_hit.x() + rx_axis.y() * to_hit.y();
  const double left = rx_axis.x() * to_hit.y() - rx_axis.y() * to_hit.x();
  const double azimuth = std::atan2(left, forward);
  const double elevation =
      std::asin(std::clamp(to_hit.z() / rx_leg_m, -1.0, 1.0)) + sonar_.tilt_deg * kDegToRad;
  const double rx_pattern = one_way_pattern(azimuth, elevation, sonar_) / pattern_norm_;
  const double received = power * rx_pattern * two_way_loss(path_m, sonar_.absorption_db_per_m);
  // Bin j holds ranges [(j + 1/2) bin, (j + 3/2) bin); the echo covers [range -+ extent / 2] at a
  // uniform density, shared among the bins by overlap (all in one bin when the extent is 0).
  const double lo_m = std::max(range_m - 0.5 * extent_m, sonar_.min_range_m);
  const double hi_m = range_m + 0.5 * extent_m;
  const double bins_m = sonar_.bins * sonar_.bin_m;
  if (hi_m < sonar_.min_range_m || lo_m >= bins_m + 0.5 * sonar_.bin_m) return;
  const auto bin_of = [&](double r_m) {
    return std::clamp(static_cast<long>(std::floor(r_m / sonar_.bin_m - 0.5)), 0L,
                      static_cast<long>(sonar_.bins) - 1);
  };
  const long first = bin_of(lo_m), last = bin_of(hi_m);
  Echoes::Contribution c{first, last, 0.0, 0.0, 0.0, material_id};
  if (extent_m <= 0.0) {
    c.first = c.last = bin_of(range_m);
    c.at_first = c.at_last = received;
  } else {
    // Partial first and last bins directly, the whole bins between as one step up and down;
    // what lies under the minimum range or beyond the last bin is lost.
    const double per_m = received / extent_m;
    const double end_m = std::min(hi_m, bins_m + 0.5 * sonar_.bin_m);
    const double first_edge_m = (static_cast<double>(first) + 1.5) * sonar_.bin_m;
    const double last_edge_m = (static_cast<double>(last) + 0.5) * sonar_.bin_m;
    if (first == last) {
      c.at_first = c.at_last = per_m * (end_m - lo_m);
    } else {
      c.at_first = per_m * (first_edge_m - lo_m);
      c.at_last = per_m * (end_m - last_edge_m);
      c.between = per_m * sonar_.bin_m;
      std::vector<double>& steps = multipath ? echoes.multipath_steps : echoes.direct_steps;
      steps[static_cast<std::size_t>(first) + 1] += c.between;
      steps[static_cast<std::size_t>(last)] -= c.between;
    }
  }
  std::vector<double>& profile = multipath ? echoes.multipath : echoes.direct;
  profile[static_cast<std::size_t>(c.first)] += c.at_first;
  if (c.last != c.first) profile[static_cast<std::size_t>(c.last)] += c.at_last;
  echoes.contributions.push_back(c);
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
  // Speckle belongs to the echo as it arrives (scatterers interfering within a resolution
  // cell): Rayleigh amplitude = exponential power, averaged over L independent looks (the bin's
  // samples), Gamma(L, 1/L) with mean 1. The pulse and the receiver filter then smooth the
  // speckled echo, so its tail decays with the echo instead of flickering bin by bin.
  std::vector<double> echo(static_cast<std::size_t>(sonar_.bins));
  for (std::size_t k = 0; k < echo.size(); ++k) {
    echo[k] = echoes.direct[k] + echoes.multipath[k];
    if (!sonar_.speckle || echo[k] == 0.0) continue;
    double looks = 0.0;
    for (int l = 0; l < sonar_.speckle_looks; ++l) looks += exponential(rng);
    echo[k] *= looks / sonar_.speckle_looks;
  }
  spread_in_range(pulse_kernel_, echo);
  std::vector<std::uint8_t> intensity(echo.size());
  for (std::size_t k = 0; k < intensity.size(); ++k) {
    // No echo and even the largest noise draw stays under intensity 1: 0, no draw needed.
    if (echo[k] == 0.0 && noise_power * kMaxExponential * tvg_linear_[k] < level_thresholds_[1]) {
      continue;
    }
    // Background noise: exponential power after the receiver.
    const double power = echo[k] + noise_power * exponential(rng);
    // intensity = round(255 (10 log10(power x tvg) - min_db) / span_db), clamped to 0..255:
    // the number of quantisation boundaries the shown power reaches.
    intensity[k] = quantise(power * tvg_linear_[k]);
  }
  return intensity;
}

}  // namespace msislab::sim
