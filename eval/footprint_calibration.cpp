#include "eval/footprint_calibration.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace msislab {

namespace {

/// The index of the node nearest x (nodes ascending, at least one).
std::size_t nearest_node(const std::vector<double>& nodes, double x) {
  const auto above = std::lower_bound(nodes.begin(), nodes.end(), x);
  if (above == nodes.begin()) return 0;
  if (above == nodes.end()) return nodes.size() - 1;
  const std::size_t i = static_cast<std::size_t>(above - nodes.begin());
  return x - nodes[i - 1] <= nodes[i] - x ? i - 1 : i;
}

/// The beam of the truth taken within 1 ms of t_s, or end.
std::vector<AxisTruth>::const_iterator beam_at(const std::vector<AxisTruth>& beams, double t_s) {
  constexpr double kSameBeam_s = 1e-3;
  const auto beam = std::lower_bound(beams.begin(), beams.end(), t_s - kSameBeam_s,
                                     [](const AxisTruth& b, double t) { return b.t_s < t; });
  if (beam == beams.end() || std::abs(beam->t_s - t_s) > kSameBeam_s) return beams.end();
  return beam;
}

}  // namespace

std::vector<double> bearing_offsets_rad(const std::vector<PlacedScan>& scans,
                                        const std::vector<AxisTruth>& beams,
                                        double max_range_gap_m) {
  std::vector<double> offsets;
  for (const PlacedScan& placed : scans) {
    for (const ScanPoint& p : placed.scan.points) {
      const auto beam = beam_at(beams, p.t_s);
      if (beam == beams.end() || !beam->strongest_range_m || !beam->strongest_bearing_offset_rad) {
        continue;
      }
      const double range_m = (p.p_m - p.p_sonar_m).norm();
      if (std::abs(range_m - *beam->strongest_range_m) > max_range_gap_m) continue;
      offsets.push_back(*beam->strongest_bearing_offset_rad);
    }
  }
  return offsets;
}

std::vector<FootprintSample> footprint_samples(const std::vector<PlacedScan>& scans,
                                               const std::vector<AxisTruth>& beams,
                                               const LineNormalConfig& line) {
  std::vector<FootprintSample> samples;
  for (const PlacedScan& placed : scans) {
    const std::vector<ScanPoint>& points = placed.scan.points;
    const std::vector<Eigen::Vector2d> normals = line_normals(points, line);
    for (std::size_t k = 0; k < points.size(); ++k) {
      if (normals[k].isZero()) continue;
      const auto beam = beam_at(beams, points[k].t_s);
      if (beam == beams.end() || !beam->first_hit_range_m) continue;
      const Eigen::Vector2d ray = points[k].p_m - points[k].p_sonar_m;
      FootprintSample s;
      s.range_m = ray.norm();
      if (!(s.range_m > 0.0)) continue;
      s.incidence_rad = std::acos(std::min(1.0, std::abs(ray.dot(normals[k])) / s.range_m));
      s.offset_m = s.range_m - *beam->first_hit_range_m;
      if (beam->strongest_range_m && beam->strongest_bearing_offset_rad &&
          std::abs(s.range_m - *beam->strongest_range_m) <= kSameEchoRange_m) {
        // A turn counter-clockwise by theta moves the axis a by theta perp(a); it turns toward
        // the wall's normal (into the wall) when perp(a) . n_into > 0, n_into the normal
        // pointing away from the head.
        const Eigen::Vector2d a = ray / s.range_m;
        const Eigen::Vector2d n_into = a.dot(normals[k]) >= 0.0 ? normals[k] : -normals[k];
        const Eigen::Vector2d perp(-a.y(), a.x());
        s.bearing_toward_normal_rad = perp.dot(n_into) >= 0.0
                                          ? *beam->strongest_bearing_offset_rad
                                          : -*beam->strongest_bearing_offset_rad;
      }
      samples.push_back(s);
    }
  }
  return samples;
}

FootprintEstimate estimate_footprint(const std::vector<FootprintSample>& samples,
                                     const FootprintGrid& grid) {
  const std::size_t n = grid.incidences_rad.size();
  const std::size_t cells = grid.ranges_m.size() * n;
  FootprintEstimate out;
  out.table.ranges_m = grid.ranges_m;
  out.table.incidences_rad = grid.incidences_rad;
  out.samples.assign(cells, 0);
  if (cells == 0) return out;
  // Welford's running mean and sum of squares per cell.
  std::vector<double> mean(cells, 0.0), m2(cells, 0.0);
  out.bearing_samples.assign(n, 0);
  std::vector<double> sum_b(n, 0.0), sum_b2(n, 0.0);
  for (const FootprintSample& s : samples) {
    if (!(std::abs(s.offset_m) <= grid.max_abs_offset_m)) {
      ++out.left_out;
      continue;
    }
    const std::size_t j = nearest_node(grid.incidences_rad, s.incidence_rad);
    const std::size_t c = nearest_node(grid.ranges_m, s.range_m) * n + j;
    if (std::isfinite(s.bearing_toward_normal_rad)) {
      ++out.bearing_samples[j];
      sum_b[j] += s.bearing_toward_normal_rad;
      sum_b2[j] += s.bearing_toward_normal_rad * s.bearing_toward_normal_rad;
    }
    const int count = ++out.samples[c];
    const double step = s.offset_m - mean[c];
    mean[c] += step / count;
    m2[c] += step * (s.offset_m - mean[c]);
  }
  constexpr double kNan = std::numeric_limits<double>::quiet_NaN();
  const int min_samples = std::max(2, grid.min_samples);
  for (std::size_t j = 0; j < n; ++j) {
    const int count = out.bearing_samples[j];
    const bool enough = count >= min_samples;
    out.bearing_toward_normal_mean_rad.push_back(enough ? sum_b[j] / count : kNan);
    out.bearing_toward_normal_rms_rad.push_back(enough ? std::sqrt(sum_b2[j] / count) : kNan);
  }
  for (std::size_t c = 0; c < cells; ++c) {
    const bool enough = out.samples[c] >= min_samples;
    out.table.offset_m.push_back(enough ? mean[c] : kNan);
    out.table.sd_m.push_back(enough ? std::sqrt(m2[c] / (out.samples[c] - 1)) : kNan);
  }
  return out;
}

}  // namespace msislab
