#include "sim/msis_receiver.hpp"

#include <algorithm>
#include <cmath>

#include "geometry/angles.hpp"
#include "sim/lanes.hpp"
#include "sim/sonar_physics.hpp"

namespace msislab::sim {

MsisReceiver::MsisReceiver(const SonarConfig& sonar, double pattern_norm)
    : sonar_(sonar),
      pattern_norm_(pattern_norm),
      gaussian_pattern_(sonar.beam_pattern == BeamPattern::kGaussian),
      absorption_per_m_(two_way_absorption_per_m(sonar.absorption_db_per_m)),
      noise_power_(std::pow(10.0, sonar.noise_level_db / 10.0)),
      range_scale_(range_scale(sonar)),
      water_sound_speed_mps_(sonar.water_sound_speed_mps.value_or(sonar.sound_speed_mps)) {
  // pattern_1d's Gaussian exp(-ln2 u^2 / 2) with u = 2 angle / width.
  const double h_width = sonar.horizontal_beamwidth_deg * kDegToRad;
  const double v_width = sonar.vertical_beamwidth_deg * kDegToRad;
  log_pattern_azimuth_per_rad2_ = 2.0 * kLn2 / (h_width * h_width);
  log_pattern_elevation_per_rad2_ = 2.0 * kLn2 / (v_width * v_width);
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

void MsisReceiver::receive_geometry(const Ping& ping, const Echo& echo, ReceiverScratch& scratch,
                                    std::size_t i) const {
  // Received at t + 2 path / c (c the water's): the last leg of the return runs from the first
  // surface on the route to where the head is then, and the receive pattern is taken there.
  const double w =
      std::clamp(2.0 * echo.path_m / water_sound_speed_mps_ / ping.rx_window_s, 0.0, 1.0);
  const Eigen::Vector3f rx_m =
      ping.tx.position_m + static_cast<float>(w) * (ping.rx_last.position_m - ping.tx.position_m);
  const Eigen::Vector2d rx_axis =
      (ping.tx.axis + w * (ping.rx_last.axis - ping.tx.axis)).normalized();
  const Eigen::Vector3f to_hit = echo.first_hit_m - rx_m;
  const double rx_leg_m = to_hit.norm();
  const double tx_leg_m = (echo.first_hit_m - ping.tx.position_m).norm();
  scratch.range_m[i] = (2.0 * echo.path_m - tx_leg_m + rx_leg_m) / 2.0;
  // The return direction in the receive head's frame: forward along the axis, left across it.
  scratch.forward_m[i] = rx_axis.x() * to_hit.x() + rx_axis.y() * to_hit.y();
  scratch.left_m[i] = rx_axis.x() * to_hit.y() - rx_axis.y() * to_hit.x();
  scratch.sin_elevation[i] = std::clamp(to_hit.z() / rx_leg_m, -1.0, 1.0);
  // power x receive pattern x two-way loss (two_way_loss, sim/sonar_physics), with the roughness,
  // the absorption and a Gaussian pattern under one exp.
  scratch.exponent[i] = echo.log_gain - absorption_per_m_ * echo.path_m;
}

void MsisReceiver::add_echoes(const Ping& ping, const std::vector<Echo>& echoes,
                              EchoProfile& profile, ReceiverScratch& scratch) const {
  const std::size_t n = echoes.size();
  for (auto* v : {&scratch.range_m, &scratch.forward_m, &scratch.left_m, &scratch.sin_elevation,
                  &scratch.exponent, &scratch.received}) {
    v->resize(n + 1);  // an even count for the blocks of two
  }
  for (std::size_t i = 0; i < n; ++i) receive_geometry(ping, echoes[i], scratch, i);
  // The padding lane: a return straight ahead.
  scratch.forward_m[n] = 1.0;
  scratch.left_m[n] = scratch.sin_elevation[n] = scratch.exponent[n] = 0.0;
  const double tilt_rad = sonar_.tilt_deg * kDegToRad;
  using namespace lanes;
  for (std::size_t i = 0; i < n; i += kLanes) {
    const Lanes azimuth = lanes::atan2(load(scratch.left_m, i), load(scratch.forward_m, i));
    const Lanes elevation = add(lanes::asin(load(scratch.sin_elevation, i)), tilt_rad);
    Lanes exponent = load(scratch.exponent, i);
    if (gaussian_pattern_) {
      exponent =
          sub(exponent, add(mul(mul(azimuth, azimuth), log_pattern_azimuth_per_rad2_),
                            mul(mul(elevation, elevation), log_pattern_elevation_per_rad2_)));
    }
    store(lanes::exp(exponent), scratch.received, i);
    if (!gaussian_pattern_) {
      for (std::size_t k = 0; k < kLanes && i + k < n; ++k) {
        scratch.received[i + k] *= one_way_pattern(lane(azimuth, k), lane(elevation, k), sonar_);
      }
    }
  }
  for (std::size_t i = 0; i < n; ++i) {
    const double received =
        echoes[i].power / pattern_norm_ * scratch.received[i] / two_way_spreading(echoes[i].path_m);
    // The sonar turns the echo's time into range with its own sound speed: range and extent
    // as it reports them.
    lay_over_bins(echoes[i], range_scale_ * scratch.range_m[i], range_scale_ * echoes[i].extent_m,
                  received, profile);
  }
}

void MsisReceiver::lay_over_bins(const Echo& echo, double range_m, double extent_m, double received,
                                 EchoProfile& profile) const {
  // Bin j holds ranges [(j + 1/2) bin, (j + 3/2) bin); the echo covers [range -+ extent / 2] at a
  // uniform density, shared among the bins by overlap (all in one bin when the extent is 0).
  const double lo_m = std::max(range_m - 0.5 * extent_m, sonar_.min_range_m);
  const double hi_m = range_m + 0.5 * extent_m;
  const double bins_m = sonar_.bins * sonar_.bin_m;
  if (hi_m < sonar_.min_range_m || lo_m >= bins_m + 0.5 * sonar_.bin_m) return;
  const auto bin_of = [&](double r) {
    // Truncation, not floor: the two differ only below 0, which the clamp maps to bin 0 anyway.
    return std::clamp(static_cast<long>(r / sonar_.bin_m - 0.5), 0L,
                      static_cast<long>(sonar_.bins) - 1);
  };
  const long first = bin_of(lo_m), last = bin_of(hi_m);
  EchoProfile::Contribution c{first, last, 0.0, 0.0, 0.0, echo.material_id, echo.first_hit_m};
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
      std::vector<double>& steps = echo.multipath ? profile.multipath_steps : profile.direct_steps;
      steps[static_cast<std::size_t>(first) + 1] += c.between;
      steps[static_cast<std::size_t>(last)] -= c.between;
    }
  }
  std::vector<double>& bins = echo.multipath ? profile.multipath : profile.direct;
  bins[static_cast<std::size_t>(c.first)] += c.at_first;
  if (c.last != c.first) bins[static_cast<std::size_t>(c.last)] += c.at_last;
  profile.contributions.push_back(c);
}

std::uint8_t MsisReceiver::quantise(double shown) const {
  // Branchless binary search for the last boundary <= shown (entry 0 is below every power).
  std::size_t at = 0;
  for (std::size_t half = 128; half > 0; half /= 2) {
    at += static_cast<std::size_t>(level_thresholds_[at + half] <= shown) * half;
  }
  return static_cast<std::uint8_t>(at);
}

std::vector<std::uint8_t> MsisReceiver::to_intensity(std::uint32_t first_bin,
                                                     const std::vector<double>& power, Rng& rng,
                                                     std::vector<double>& echo) const {
  static const ExponentialTable exponential;
  const double kMaxExponential = ExponentialTable::max();
  // Speckle belongs to the echo as it arrives (scatterers interfering within a resolution
  // cell): Rayleigh amplitude = exponential power, averaged over L independent looks (the bin's
  // samples), Gamma(L, 1/L) with mean 1. The pulse and the receiver filter then smooth the
  // speckled echo, so its tail decays with the echo instead of flickering bin by bin.
  echo.assign(static_cast<std::size_t>(sonar_.bins), 0.0);
  std::copy(power.begin(), power.end(), echo.begin() + first_bin);
  for (std::size_t k = first_bin; k < first_bin + power.size(); ++k) {
    if (!sonar_.speckle || echo[k] == 0.0) continue;
    double looks = 0.0;
    for (int l = 0; l < sonar_.speckle_looks; ++l) looks += exponential(rng);
    echo[k] *= looks / sonar_.speckle_looks;
  }
  spread_in_range(pulse_kernel_, echo);
  std::vector<std::uint8_t> intensity(echo.size());
  for (std::size_t k = 0; k < intensity.size(); ++k) {
    // No echo and even the largest noise draw stays under intensity 1: 0, no draw needed.
    if (echo[k] == 0.0 && noise_power_ * kMaxExponential * tvg_linear_[k] < level_thresholds_[1]) {
      continue;
    }
    // Background noise: exponential power after the receiver.
    const double received = echo[k] + noise_power_ * exponential(rng);
    // intensity = round(255 (10 log10(power x tvg) - min_db) / span_db), clamped to 0..255:
    // the number of quantisation boundaries the shown power reaches.
    intensity[k] = quantise(received * tvg_linear_[k]);
  }
  return intensity;
}

}  // namespace msislab::sim
