// The local surface normal of each reference point of a scan, for point-to-line residuals (Censi,
// ICRA 2007 and 2008): the neighbours of a point within a radius are fitted by principal
// components; when their scatter is a thin line (smallest over largest eigenvalue below a ratio),
// the normal is the eigenvector of the smallest eigenvalue. Points without a clear line (corners,
// clutter, isolated returns) get a zero vector: their residuals stay point-to-point.
#pragma once

#include <Eigen/Core>
#include <vector>

#include "slam/scan_builder.hpp"

namespace msislab {

struct LineNormalConfig {
  double radius_m = 1.5;  ///< neighbours of a point closer than this (m), the point included
  int min_points = 5;     ///< fewer neighbours: no line
  double max_eigen_ratio = 0.05;  ///< lambda_min / lambda_max of the neighbours' scatter (unitless)
};

/// Unit normal per point, or zero where the neighbourhood is not a line.
std::vector<Eigen::Vector2d> line_normals(const std::vector<ScanPoint>& points,
                                          const LineNormalConfig& config);

}  // namespace msislab
