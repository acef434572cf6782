#include "slam/beam_segmentation.hpp"

#include <algorithm>
#include <cassert>
#include <cmath>
#include <cstddef>

namespace msislab {
namespace {

using Profile = std::vector<std::uint8_t>;

// Bin j lies at (j + 1) x bin_m; the first bin kept is the first at range >= min_range_m. The
// small tolerance keeps a bin exactly at the minimum range despite rounding of the division.
std::size_t first_bin_at(double min_range_m, double bin_m) {
  const double j = std::ceil(min_range_m / bin_m - 1.0 - 1e-9);
  return j <= 0.0 ? 0 : static_cast<std::size_t>(j);
}

double range_of_bin(std::size_t j, double bin_m) { return static_cast<double>(j + 1) * bin_m; }

// Index of the largest value in [begin, end); ties go to the nearest bin.
template <typename Values>
std::size_t argmax(const Values& values, std::size_t begin, std::size_t end) {
  std::size_t best = begin;
  for (std::size_t j = begin + 1; j < end; ++j) {
    if (values[j] > values[best]) best = j;
  }
  return best;
}

// A run of consecutive bins [begin, end) at or above the threshold.
struct Run {
  std::size_t begin = 0;
  std::size_t end = 0;
};

// The next run at or after bin `from`; begin == end == size when there is none.
template <typename Values>
Run next_run(const Values& values, std::size_t from, double threshold) {
  const std::size_t n = values.size();
  Run run{n, n};
  std::size_t j = from;
  while (j < n && static_cast<double>(values[j]) < threshold) ++j;
  run.begin = j;
  while (j < n && static_cast<double>(values[j]) >= threshold) ++j;
  run.end = j;
  return run;
}

std::vector<double> max_intensity(const Profile& intensity, double bin_m,
                                  const SegmentationConfig& config) {
  const std::size_t first = first_bin_at(config.min_range_m, bin_m);
  if (first >= intensity.size()) return {};
  const std::size_t best = argmax(intensity, first, intensity.size());
  if (static_cast<double>(intensity[best]) < config.threshold) return {};
  return {range_of_bin(best, bin_m)};
}

std::vector<double> threshold_groups(const Profile& intensity, double bin_m,
                                     const SegmentationConfig& config) {
  std::vector<double> ranges_m;
  const auto wanted = static_cast<std::size_t>(std::max(config.max_ranges_per_beam, 0));
  const auto min_bins = static_cast<std::size_t>(std::max(config.min_run_bins, 1));
  std::size_t from = first_bin_at(config.min_range_m, bin_m);
  while (ranges_m.size() < wanted) {
    const Run run = next_run(intensity, from, config.threshold);
    if (run.begin >= run.end) break;
    if (run.end - run.begin >= min_bins) {
      ranges_m.push_back(range_of_bin(argmax(intensity, run.begin, run.end), bin_m));
    }
    from = run.end;
  }
  return ranges_m;
}

// Centred moving average over `window` bins of values[first..]; the window shrinks at both ends
// so that the ignored near bins do not leak into the kept ones.
std::vector<double> moving_average(const Profile& values, std::size_t first, int window) {
  const std::size_t n = values.size();
  const auto half = static_cast<std::size_t>(std::max(window, 1) / 2);
  std::vector<double> smoothed(n, 0.0);
  for (std::size_t j = first; j < n; ++j) {
    const std::size_t begin = std::max(first + half, j) - half;
    const std::size_t end = std::min(n, j + half + 1);
    double sum = 0.0;
    for (std::size_t k = begin; k < end; ++k) sum += values[k];
    smoothed[j] = sum / static_cast<double>(end - begin);
  }
  return smoothed;
}

std::vector<double> smoothed_first(const Profile& intensity, double bin_m,
                                   const SegmentationConfig& config) {
  const std::size_t first = first_bin_at(config.min_range_m, bin_m);
  if (first >= intensity.size()) return {};
  const std::vector<double> smoothed = moving_average(intensity, first, config.smoothing_bins);
  const Run run = next_run(smoothed, first, config.threshold);
  if (run.begin >= run.end) return {};
  // Smoothing finds the return; the raw peak inside it locates the surface without the blur.
  return {range_of_bin(argmax(intensity, run.begin, run.end), bin_m)};
}

}  // namespace

std::vector<double> segment_profile(const std::vector<std::uint8_t>& intensity, double bin_m,
                                    const SegmentationConfig& config) {
  assert(bin_m > 0.0);
  switch (config.method) {
    case SegmentationMethod::kMaxIntensity:
      return max_intensity(intensity, bin_m, config);
    case SegmentationMethod::kThresholdGroups:
      return threshold_groups(intensity, bin_m, config);
    case SegmentationMethod::kSmoothedFirst:
      return smoothed_first(intensity, bin_m, config);
  }
  return {};
}

std::vector<double> segment_detections(const std::vector<double>& detected_ranges_m, double bin_m,
                                       const SegmentationConfig& config) {
  assert(bin_m > 0.0);
  std::vector<double> kept_m;
  for (const double r : detected_ranges_m) {
    if (r >= config.min_range_m) kept_m.push_back(r);
  }
  std::sort(kept_m.begin(), kept_m.end());
  // Neighbours two bins apart (one missing bin between) belong to the same return; 2.5 bins
  // separates that from a gap of two missing bins with margin for rounded ranges.
  const double max_step_m = 2.5 * bin_m;
  const auto wanted = static_cast<std::size_t>(std::max(config.max_ranges_per_beam, 0));
  std::vector<double> ranges_m;
  std::size_t begin = 0;
  while (begin < kept_m.size() && ranges_m.size() < wanted) {
    std::size_t end = begin + 1;
    while (end < kept_m.size() && kept_m[end] - kept_m[end - 1] <= max_step_m) ++end;
    ranges_m.push_back(0.5 * (kept_m[begin] + kept_m[end - 1]));
    begin = end;
  }
  return ranges_m;
}

std::string to_string(SegmentationMethod method) {
  switch (method) {
    case SegmentationMethod::kMaxIntensity:
      return "max_intensity";
    case SegmentationMethod::kThresholdGroups:
      return "threshold_groups";
    case SegmentationMethod::kSmoothedFirst:
      return "smoothed_first";
  }
  return "unknown";
}

bool parse_segmentation_method(const std::string& name, SegmentationMethod& method) {
  for (const SegmentationMethod m :
       {SegmentationMethod::kMaxIntensity, SegmentationMethod::kThresholdGroups,
        SegmentationMethod::kSmoothedFirst}) {
    if (name == to_string(m)) {
      method = m;
      return true;
    }
  }
  return false;
}

}  // namespace msislab
