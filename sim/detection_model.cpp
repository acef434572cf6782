#include "sim/detection_model.hpp"

#include <algorithm>
#include <cmath>

namespace msislab {

std::vector<double> moving_mean(const std::vector<double>& x, int window) {
  const int n = static_cast<int>(x.size());
  const int w = std::max(window, 1);
  const int behind = w / 2;
  const int ahead = w - 1 - behind;  // (w - 1) / 2 for odd w, w / 2 - 1 for even w
  // Prefix sums make every window mean O(1).
  std::vector<double> prefix(static_cast<std::size_t>(n) + 1, 0.0);
  for (int j = 0; j < n; ++j) prefix[j + 1] = prefix[j] + x[j];
  std::vector<double> mean(static_cast<std::size_t>(n));
  for (int j = 0; j < n; ++j) {
    const int lo = std::max(j - behind, 0);
    const int hi = std::min(j + ahead + 1, n);
    mean[j] = (prefix[hi] - prefix[lo]) / (hi - lo);
  }
  return mean;
}

std::vector<int> detect_bins(const std::vector<std::uint8_t>& intensity, double bin_m,
                             const DetectionModelConfig& config) {
  const int n = static_cast<int>(intensity.size());
  // First bin at or beyond the minimum range; the tolerance keeps a bin exactly there.
  const int first =
      std::clamp(static_cast<int>(std::ceil(config.min_range_m / bin_m - 1.0 - 1e-9)), 0, n);
  const std::vector<double> kept(intensity.begin() + first, intensity.end());
  const std::vector<double> smoothed = moving_mean(kept, config.smoothing_bins);
  const int last = n - 1 - first;  // linspace(0, r, 1) is r, as in MATLAB
  std::vector<int> detected;
  for (int k = 0; k <= last; ++k) {
    const double ramp = last > 0 ? config.ramp_max * k / last : config.ramp_max;
    if (smoothed[k] - ramp > config.threshold) detected.push_back(first + k);
  }
  return detected;
}

}  // namespace msislab
