// The receiving side of the MSIS (docs/simulator.md): each echo laid over the range bins with the
// receive pattern and the transmission loss, then the profile to intensities with speckle, the
// pulse's spread, noise, gain, TVG and quantisation.
#pragma once

#include <cstdint>
#include <vector>

#include "sim/msis_beam.hpp"
#include "sim/random.hpp"
#include "sim/scenario.hpp"

namespace msislab::sim {

/// Working memory of MsisReceiver::add_echoes, reused across beams.
struct ReceiverScratch {
  std::vector<double> range_m;        ///< two-way range / 2 of each echo
  std::vector<double> forward_m;      ///< the return direction along the receive axis
  std::vector<double> left_m;         ///< and across it
  std::vector<double> sin_elevation;  ///< of the return direction
  std::vector<double> exponent;       ///< of the received power's exp
  std::vector<double> received;       ///< the received power
};

class MsisReceiver {
 public:
  /// `pattern_norm` divides every one-way pattern value (the transmitter's normalisation).
  MsisReceiver(const SonarConfig& sonar, double pattern_norm);

  /// Adds each echo, spread uniformly over its range -+ extent / 2, to the profile, in order:
  /// received at t + 2 path / c by the head where it is then, through the receive pattern and
  /// the two-way loss; the angles and exps computed in blocks (SLEEF's vector functions).
  void add_echoes(const Ping& ping, const std::vector<Echo>& echoes, EchoProfile& profile,
                  ReceiverScratch& scratch) const;

  /// A beam's echo power as displayed intensities: power[k] is bin first_bin + k, the other bins
  /// received nothing. rng supplies this beam's speckle and noise; `scratch` is working memory,
  /// reused across beams.
  std::vector<std::uint8_t> to_intensity(std::uint32_t first_bin, const std::vector<double>& power,
                                         Rng& rng, std::vector<double>& scratch) const;

  /// Gain + TVG of a bin as a power ratio.
  double tvg(std::size_t bin) const { return tvg_linear_[bin]; }

 private:
  std::uint8_t quantise(double shown_power) const;
  /// The return's geometry and the received power's exponent, before the angles' functions.
  void receive_geometry(const Ping& ping, const Echo& echo, ReceiverScratch& scratch,
                        std::size_t i) const;
  /// Lays an echo of `received` power reported at range_m with extent_m (the sonar's ranges)
  /// over the bins.
  void lay_over_bins(const Echo& echo, double range_m, double extent_m, double received,
                     EchoProfile& profile) const;

  SonarConfig sonar_;
  double pattern_norm_;
  bool gaussian_pattern_;
  /// A Gaussian pattern's logarithm: ln b(az, el) = -(a_h az^2 + a_v el^2), these two a.
  double log_pattern_azimuth_per_rad2_ = 0.0;
  double log_pattern_elevation_per_rad2_ = 0.0;
  double absorption_per_m_;  ///< exp(-this x path) is the absorption of both ways
  double noise_power_;
  double range_scale_;                ///< range_scale(sonar): reported range per true range
  double water_sound_speed_mps_;      ///< the speed the echoes travel at
  std::vector<double> tvg_linear_;    ///< gain + TVG per bin as a power ratio
  std::vector<double> pulse_kernel_;  ///< echo spread over later bins by pulse and receiver
  /// Quantisation: intensity k is shown for levels from step k - 1/2 to k + 1/2 of the display
  /// range; entry k (1..255) is the lower boundary of k as a power ratio, entry 0 is 0.
  std::vector<double> level_thresholds_;
};

}  // namespace msislab::sim
