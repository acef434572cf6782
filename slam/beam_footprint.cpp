#include "slam/beam_footprint.hpp"

#include <algorithm>
#include <cmath>

namespace msislab {

namespace {

/// The node below x and the weight of the node above it (0 at or below the first node, 1 at or
/// beyond the last: clamped).
void bracket(const std::vector<double>& nodes, double x, std::size_t& i, double& w) {
  if (nodes.size() < 2 || x <= nodes.front()) {
    i = 0;
    w = 0.0;
    return;
  }
  if (x >= nodes.back()) {
    i = nodes.size() - 2;
    w = 1.0;
    return;
  }
  i = static_cast<std::size_t>(std::upper_bound(nodes.begin(), nodes.end(), x) - nodes.begin()) - 1;
  w = (x - nodes[i]) / (nodes[i + 1] - nodes[i]);
}

}  // namespace

bool footprint_offset(const FootprintTable& table, double range_m, double incidence_rad,
                      double& offset_m, double& sd_m) {
  if (table.empty()) return false;
  std::size_t i = 0, j = 0;
  double u = 0.0, v = 0.0;
  bracket(table.ranges_m, range_m, i, u);
  bracket(table.incidences_rad, incidence_rad, j, v);
  const std::size_t n = table.incidences_rad.size();
  const std::size_t i1 = std::min(i + 1, table.ranges_m.size() - 1);
  const std::size_t j1 = std::min(j + 1, n - 1);
  offset_m = 0.0;
  double variance = 0.0;
  const std::size_t rows[2] = {i, i1};
  const std::size_t cols[2] = {j, j1};
  const double wr[2] = {1.0 - u, u};
  const double wc[2] = {1.0 - v, v};
  for (int a = 0; a < 2; ++a) {
    for (int b = 0; b < 2; ++b) {
      const double w = wr[a] * wc[b];
      if (w == 0.0) continue;
      const double o = table.offset_m[rows[a] * n + cols[b]];
      const double s = table.sd_m[rows[a] * n + cols[b]];
      if (!std::isfinite(o) || !std::isfinite(s)) return false;
      offset_m += w * o;
      variance += w * s * s;
    }
  }
  sd_m = std::sqrt(variance);
  return true;
}

FootprintCorrection correct_footprint(std::vector<ScanPoint>& points, const FootprintTable& table,
                                      const LineNormalConfig& normals) {
  FootprintCorrection out;
  if (table.empty()) return out;
  // The normals of the scan as read: a point is looked up at the incidence its own scan shows
  // (the footprint turns a wall's apparent direction by little: docs/scan_matching.md).
  const std::vector<Eigen::Vector2d> n = line_normals(points, normals);
  for (std::size_t k = 0; k < points.size(); ++k) {
    ScanPoint& p = points[k];
    if (n[k].isZero()) {
      ++out.no_line;
      continue;
    }
    const Eigen::Vector2d ray = p.p_m - p.p_sonar_m;
    const double range_m = ray.norm();
    if (range_m <= 0.0) {
      ++out.no_cell;
      continue;
    }
    const Eigen::Vector2d axis = ray / range_m;
    const double incidence_rad = std::acos(std::min(1.0, std::abs(axis.dot(n[k]))));
    double offset_m = 0.0, sd_m = 0.0;
    if (!footprint_offset(table, range_m, incidence_rad, offset_m, sd_m)) {
      ++out.no_cell;
      continue;
    }
    p.p_m -= offset_m * axis;
    p.p_vehicle_m -= offset_m * (p.p_vehicle_m - p.p_vehicle_sonar_m).normalized();
    // The table's spread is the reading's whole spread along the axis (measured against truth,
    // it holds the range noise the reading already carries): the variance along the axis
    // becomes the larger of the two.
    const double extra = std::max(0.0, sd_m * sd_m - axis.dot(p.cov_reading * axis));
    const Eigen::Matrix2d along = extra * axis * axis.transpose();
    p.cov_reading += along;
    p.cov += along;
    ++out.corrected;
  }
  return out;
}

}  // namespace msislab
