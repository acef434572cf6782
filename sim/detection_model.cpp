#include "sim/detection_model.hpp"

#include <algorithm>
#include <cmath>

namespace msislab {

std::vector<int> detect_bins(const std::vector<std::uint8_t>& intensity, double bin_m,
                             const DetectionModelConfig& config) {
  const int n = static_cast<int>(intensity.size());
  const int half = std::max(config.smoothing_bins, 1) / 2;
  // Prefix sums make every window mean O(1).
  std::vector<double> prefix(static_cast<std::size_t>(n) + 1, 0.0);
  for (int j = 0; j < n; ++j) prefix[j + 1] = prefix[j] + intensity[j];
  const double ramp_per_bin = n > 1 ? config.ramp_max / (n - 1) : 0.0;
  // First bin at or beyond the minimum range; the tolerance keeps a bin exactly there.
  const int first =
      std::max(0, static_cast<int>(std::ceil(config.min_range_m / bin_m - 1.0 - 1e-9)));
  std::vector<int> detected;
  for (int j = first; j < n; ++j) {
    const int lo = std::max(j - half, 0);
    const int hi = std::min(j + half + 1, n);
    const double smoothed = (prefix[hi] - prefix[lo]) / (hi - lo);
    if (smoothed - ramp_per_bin * j > config.threshold) detected.push_back(j);
  }
  return detected;
}

}  // namespace msislab
