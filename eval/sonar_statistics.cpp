#include "eval/sonar_statistics.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <unordered_map>

namespace msislab {

namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

/// Each range's bin, round(range / bin_m), in ascending order.
std::vector<long> sorted_bins(const std::vector<double>& ranges_m, double bin_m) {
  std::vector<long> bins;
  bins.reserve(ranges_m.size());
  for (const double r : ranges_m) bins.push_back(std::lround(r / bin_m));
  std::sort(bins.begin(), bins.end());
  return bins;
}

std::vector<double> with_zeros(std::vector<double> values, std::size_t size) {
  values.resize(std::max(size, values.size()), 0.0);
  return values;
}

/// For every beam of keyframe k whose angle step has a beam in keyframe k + 1: the beam rows and
/// the time between the two.
void add_rotation(const std::vector<DetectedBeam>& beams, const std::vector<double>& times_s,
                  SonarStatistics& stats) {
  std::unordered_map<std::int32_t, const DetectedBeam*> previous, current;
  std::int32_t current_keyframe = std::numeric_limits<std::int32_t>::min();
  for (const DetectedBeam& beam : beams) {
    if (beam.keyframe != current_keyframe) {
      previous = beam.keyframe == current_keyframe + 1 ? std::move(current) : decltype(previous){};
      current.clear();
      current_keyframe = beam.keyframe;
    }
    current.try_emplace(beam.angle_idx, &beam);
    const auto before = previous.find(beam.angle_idx);
    if (before == previous.end()) continue;
    const DetectedBeam& a = *before->second;
    stats.beams_per_360.push_back(static_cast<double>(beam.beam_row - a.beam_row));
    stats.revolution_period_s.push_back(times_s[beam.beam_row] - times_s[a.beam_row]);
    previous.erase(before);
  }
}

/// The nearest run's length of each beam whose neighbouring beam rows in its keyframe have
/// detections, by the incidence their first ranges (stats.first_ranges_m, one per beam) give.
void add_run_lengths(const std::vector<DetectedBeam>& beams, double bin_m, double angle_step_rad,
                     SonarStatistics& stats) {
  const std::vector<double>& first_m = stats.first_ranges_m;
  for (std::size_t i = 1; i + 1 < beams.size(); ++i) {
    const DetectedBeam &before = beams[i - 1], &beam = beams[i], &after = beams[i + 1];
    if (before.beam_row + 1 != beam.beam_row || beam.beam_row + 1 != after.beam_row ||
        before.keyframe != beam.keyframe || after.keyframe != beam.keyframe) {
      continue;
    }
    const double incidence_deg =
        incidence_from_neighbours_deg(first_m[i - 1], first_m[i], first_m[i + 1], angle_step_rad);
    if (!std::isfinite(incidence_deg)) continue;
    const auto band = static_cast<int>(incidence_deg / kIncidenceBand_deg);
    if (band >= kIncidenceBands) continue;
    stats.run_length_by_incidence_m[static_cast<std::size_t>(band)].push_back(
        first_run_length_m(beam.ranges_m, bin_m));
  }
}

}  // namespace

std::vector<double> band_shares(const std::vector<double>& values_m, double band_m, int bands) {
  std::vector<double> shares(static_cast<std::size_t>(std::max(bands, 0)), 0.0);
  if (values_m.empty() || shares.empty()) return shares;
  const double top_m = band_m * bands;
  for (const double v : values_m) {
    if (!(v >= 0.0 && v <= top_m)) continue;
    const auto k = std::min(static_cast<std::size_t>(v / band_m), shares.size() - 1);
    shares[k] += 1.0;
  }
  for (double& s : shares) s /= static_cast<double>(values_m.size());
  return shares;
}

int count_runs(const std::vector<double>& ranges_m, double bin_m) {
  const std::vector<long> bins = sorted_bins(ranges_m, bin_m);
  int runs = bins.empty() ? 0 : 1;
  for (std::size_t i = 1; i < bins.size(); ++i) runs += bins[i] - bins[i - 1] >= 2;
  return runs;
}

double first_run_length_m(const std::vector<double>& ranges_m, double bin_m) {
  if (ranges_m.empty()) return 0.0;
  const std::vector<long> bins = sorted_bins(ranges_m, bin_m);
  std::size_t last = 0;
  while (last + 1 < bins.size() && bins[last + 1] - bins[last] <= 1) ++last;
  return static_cast<double>(bins[last] - bins[0] + 1) * bin_m;
}

double incidence_from_neighbours_deg(double r_before_m, double r_m, double r_after_m,
                                     double angle_step_rad, double max_jump_m) {
  if (!(r_m > 0.0) || !(angle_step_rad > 0.0) || std::abs(r_before_m - r_m) > max_jump_m ||
      std::abs(r_after_m - r_m) > max_jump_m) {
    return kNaN;
  }
  return std::atan(std::abs(r_after_m - r_before_m) / (r_m * 2.0 * angle_step_rad)) * 180.0 / M_PI;
}

SonarStatistics sonar_statistics(const std::vector<DetectedBeam>& beams,
                                 const std::vector<double>& beam_times_s, int beams_per_revolution,
                                 double bin_m, double angle_step_rad) {
  SonarStatistics stats;
  if (beams.empty()) return stats;
  stats.keyframes = beams.back().keyframe - beams.front().keyframe + 1;
  stats.beams =
      static_cast<std::size_t>(stats.keyframes) * static_cast<std::size_t>(beams_per_revolution);
  stats.empty_beams = stats.beams - std::min(stats.beams, beams.size());
  for (const DetectedBeam& beam : beams) {
    stats.bins_per_beam.push_back(static_cast<double>(beam.ranges_m.size()));
    stats.runs_per_beam.push_back(count_runs(beam.ranges_m, bin_m));
    stats.first_ranges_m.push_back(*std::min_element(beam.ranges_m.begin(), beam.ranges_m.end()));
    stats.detected_ranges_m.insert(stats.detected_ranges_m.end(), beam.ranges_m.begin(),
                                   beam.ranges_m.end());
  }
  stats.bins_per_beam = with_zeros(std::move(stats.bins_per_beam), stats.beams);
  stats.runs_per_beam = with_zeros(std::move(stats.runs_per_beam), stats.beams);
  add_rotation(beams, beam_times_s, stats);
  add_run_lengths(beams, bin_m, angle_step_rad, stats);
  return stats;
}

std::vector<double> readings_per_keyframe(const std::vector<DetectedBeam>& beams,
                                          const std::vector<BeamReadings>& readings) {
  if (beams.empty()) return {};
  const std::int32_t first = beams.front().keyframe;
  std::vector<double> counts(static_cast<std::size_t>(beams.back().keyframe - first + 1), 0.0);
  for (const DetectedBeam& beam : beams) {
    counts[static_cast<std::size_t>(beam.keyframe - first)] +=
        static_cast<double>(readings[static_cast<std::size_t>(beam.beam_row)].readings.size());
  }
  return counts;
}

}  // namespace msislab
