// The beam's footprint in the measurement model (docs/scan_matching.md, "The beam's footprint"):
// a sonar and its detector report a wall at a range that is not the range on the beam's axis, by
// an offset that depends on the range and on the incidence psi at which the axis meets the wall
// (measured against the simulator's truth, per sonar, detector and kind of scene). Each point of a
// scan whose neighbours draw a line (slam/line_normals.hpp) is moved back along its beam's axis by
// the offset the table gives for its range and incidence, and its reading's variance along the
// axis is raised to the table's spread. Points without a line keep their reading as it is.
#pragma once

#include <Eigen/Core>
#include <vector>

#include "slam/line_normals.hpp"
#include "slam/scan_builder.hpp"

namespace msislab {

/// The mean and standard deviation of (reported range - range on the beam's axis) on a grid of
/// the reported range (what a scan knows of a point; ranges_m ascending, outer) and the incidence
/// (incidences_rad ascending in [0, pi/2], inner); offset_m and sd_m row-major, NaN where the
/// table has no figure. Empty: no footprint model.
struct FootprintTable {
  std::vector<double> ranges_m;
  std::vector<double> incidences_rad;
  std::vector<double> offset_m;
  std::vector<double> sd_m;
  bool empty() const { return ranges_m.empty(); }
};

/// The offset and its spread at (range, incidence), bilinear between the grid's nodes and clamped
/// at its edges; false where a node it needs is NaN.
bool footprint_offset(const FootprintTable& table, double range_m, double incidence_rad,
                      double& offset_m, double& sd_m);

/// The footprint model of a SLAM run (the config's `footprint` section, docs/formats.md).
struct FootprintConfig {
  FootprintTable table;  ///< empty: points are kept as read
  /// The lines the incidence is taken from. Wider than the matcher's (1.5 m, 5 points): at the
  /// ranges of a harbour wall a 200-step revolution's readings lie 0.5-1 m apart along it, and
  /// at oblique incidence farther, so most wall points have fewer than 5 neighbours within 1.5 m.
  LineNormalConfig line{3.0, 3, 0.05};
};

struct FootprintCorrection {
  std::size_t corrected = 0;  ///< points moved
  std::size_t no_line = 0;    ///< points without a line normal, kept
  std::size_t no_cell = 0;    ///< points whose cell the table does not cover, kept
};

/// Corrects the points of one scan in place (each needs p_sonar_m, the head at its beam's time).
FootprintCorrection correct_footprint(std::vector<ScanPoint>& points, const FootprintTable& table,
                                      const LineNormalConfig& normals);

}  // namespace msislab
