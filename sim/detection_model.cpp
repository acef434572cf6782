#include "sim/detection_model.hpp"

#include <algorithm>
#include <cmath>

namespace msislab::sim {

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

namespace {
/// First bin at or beyond the minimum range; the tolerance keeps a bin exactly there.
int first_kept_bin(int n, double bin_m, double min_range_m) {
  return std::clamp(static_cast<int>(std::ceil(min_range_m / bin_m - 1.0 - 1e-9)), 0, n);
}

/// A row with its mean removed and its spectral energy up to N. The energy comes from Parseval
/// without the whole spectrum: with the mean removed X_0 = 0, and for the 2N-point DFT of a real
/// row sum_{k<N} |X_k|^2 = (2N sum x^2 - |X_N|^2) / 2.
struct SpectralRow {
  std::vector<double> x;
  double energy = 0.0;  ///< 0 for a constant row
};

SpectralRow spectral_row(const std::vector<double>& row) {
  SpectralRow r;
  const double n = static_cast<double>(row.size());
  double mean = 0.0;
  for (const double v : row) mean += v / n;
  double squares = 0.0, alternating = 0.0;
  for (std::size_t i = 0; i < row.size(); ++i) {
    r.x.push_back(row[i] - mean);
    squares += r.x.back() * r.x.back();
    alternating += (i % 2 == 0 ? 1.0 : -1.0) * r.x.back();
  }
  r.energy = 0.5 * (2.0 * n * squares - alternating * alternating);
  if (r.energy <= 1e-12 * (1.0 + 2.0 * n * squares)) r.energy = 0.0;
  return r;
}
}  // namespace

int matlab_default_window(const std::vector<std::vector<double>>& kept_profiles,
                          double smoothing_factor) {
  if (kept_profiles.empty() || kept_profiles.front().size() < 2) return 1;
  const std::size_t n = kept_profiles.front().size();
  const std::size_t m = 2 * n;
  std::vector<SpectralRow> rows;
  for (const std::vector<double>& row : kept_profiles) rows.push_back(spectral_row(row));
  // exp(-i 2 pi t / 2N) for t = 0 .. 2N - 1: the DFT's factors, indexed by k i mod 2N.
  std::vector<double> cos_t(m), sin_t(m);
  for (std::size_t t = 0; t < m; ++t) {
    cos_t[t] = std::cos(2.0 * M_PI * static_cast<double>(t) / static_cast<double>(m));
    sin_t[t] = std::sin(2.0 * M_PI * static_cast<double>(t) / static_cast<double>(m));
  }
  const double tau = 1.0 - smoothing_factor;
  std::vector<double> cumulative(rows.size(), 0.0);
  for (std::size_t k = 1; k < n; ++k) {  // k = 0 adds nothing: the means are removed
    double average = 0.0;
    for (std::size_t b = 0; b < rows.size(); ++b) {
      if (rows[b].energy == 0.0) continue;
      double re = 0.0, im = 0.0;
      std::size_t t = 0;
      for (std::size_t i = 0; i < n; ++i, t = (t + k) % m) {
        re += rows[b].x[i] * cos_t[t];
        im -= rows[b].x[i] * sin_t[t];
      }
      cumulative[b] += (re * re + im * im) / rows[b].energy;
      average += cumulative[b];
    }
    average /= static_cast<double>(rows.size());
    if (average > tau) {  // rho = k + 1 (1-based), so rho - 1 = k
      const double w = 0.44294 * static_cast<double>(m) / static_cast<double>(k);
      return static_cast<int>(std::ceil(std::sqrt(w * w + 1.0)));
    }
  }
  return 1;
}

std::vector<double> kept_bins(const std::vector<std::uint8_t>& intensity, double bin_m,
                              double min_range_m) {
  const int first = first_kept_bin(static_cast<int>(intensity.size()), bin_m, min_range_m);
  return std::vector<double>(intensity.begin() + first, intensity.end());
}

std::vector<int> detect_bins(const std::vector<std::uint8_t>& intensity, double bin_m,
                             const DetectionModelConfig& config) {
  const int n = static_cast<int>(intensity.size());
  const int first = first_kept_bin(n, bin_m, config.min_range_m);
  const std::vector<double> kept = kept_bins(intensity, bin_m, config.min_range_m);
  const std::vector<double> smoothed = moving_mean(kept, config.smoothing_bins);
  const int last = n - 1 - first;  // linspace(0, r, 1) is r, as in MATLAB
  std::vector<int> detected;
  for (int k = 0; k <= last; ++k) {
    const double ramp = last > 0 ? config.ramp_max * k / last : config.ramp_max;
    if (smoothed[k] - ramp > config.threshold) detected.push_back(first + k);
  }
  return detected;
}

}  // namespace msislab::sim
