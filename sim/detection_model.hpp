// The detector that made the St. Pere detections file, exactly as the publisher's MATLAB code runs
// it (loadingDataset/createDatasetSonarData.m and binsToPCL.m in the public repository
// timzarhansen/matlabTestEnvironment; docs/front_end.md): an echo intensity profile in, the bins it
// marks as detected out. The real data have only these marks, so the simulator runs the same
// detector on its profiles and every statistic and every pipeline stage after it sees both
// datasets the same way.
#pragma once

#include <cstdint>
#include <vector>

namespace msislab::sim {

struct DetectionModelConfig {
  int smoothing_bins = 5;  ///< movmean window along range, bins; 0: MATLAB's default window,
                           ///< chosen per revolution (matlab_default_window; docs/simulator.md)
  double smoothing_factor = 0.25;  ///< MATLAB's SmoothingFactor for the default window
  double ramp_max = 30.0;          ///< subtracted at the last kept bin; 0 at the first, linear
  double threshold = 45.0;   ///< a bin is detected when smoothed minus ramp exceeds this (strict)
  double min_range_m = 1.0;  ///< bins closer than this are dropped before the smoothing
};

/// MATLAB's movmean(x, window) with its shrinking ends: the mean of x over [i - kb, i + kf] cut to
/// the profile, kb = kf = (window - 1) / 2 for an odd window, kb = window / 2 and
/// kf = window / 2 - 1 for an even one.
std::vector<double> moving_mean(const std::vector<double>& x, int window);

/// MATLAB's default window of smoothdata(A, 2) for one revolution, A = `kept_profiles` (one row
/// per beam, the kept bins, all rows of one length N): each row's mean removed, its power spectrum
/// |X_k|^2 of the 2N-point DFT for k = 0 .. N - 1 normalised to sum 1 and accumulated (a constant
/// row counts as all zeros); the accumulated curves averaged over the rows; rho the first 1-based
/// index where the average exceeds 1 - smoothing_factor; the window
/// ceil(sqrt((0.44294 x 2N / max(rho - 1, 1))^2 + 1)), or 1 when no index does.
int matlab_default_window(const std::vector<std::vector<double>>& kept_profiles,
                          double smoothing_factor = 0.25);

/// The kept bins of a profile (from the first bin at or beyond min_range_m), as doubles.
std::vector<double> kept_bins(const std::vector<std::uint8_t>& intensity, double bin_m,
                              double min_range_m);

/// Indices j of the detected bins of a profile whose bin j lies at (j + 1) x bin_m, ascending.
/// With K the first bin at or beyond min_range_m and n the profile's length, over the kept bins
/// j = K .. n - 1 only (the dropped bins never enter a mean):
///   s_j    = moving_mean(intensity[K .. n - 1], smoothing_bins) at j,
///   ramp_j = ramp_max x (j - K) / (n - 1 - K)     (MATLAB's linspace(0, ramp_max, n - K)),
///   detected  <=>  s_j - ramp_j > threshold.
/// (The publisher also zeroes values under 30 before the threshold; that never changes a bin
/// above 45, so it is not modelled.)
std::vector<int> detect_bins(const std::vector<std::uint8_t>& intensity, double bin_m,
                             const DetectionModelConfig& config);

}  // namespace msislab::sim
