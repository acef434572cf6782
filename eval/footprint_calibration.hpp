// The beam's footprint measured against a simulation's truth (docs/scan_matching.md, "The beam's
// footprint"): for every reading of a scan that lies on a line, its range, the incidence its
// scan shows (the angle between its beam's axis and the line's normal) and its offset, the range
// reported less the range at which the beam's axis first meets a surface (truth/beams.csv);
// then, per cell of a grid of range and incidence, the offsets' mean and standard deviation:
// the table slam/beam_footprint.hpp corrects scans with.
#pragma once

#include <optional>
#include <vector>

#include "slam/beam_footprint.hpp"
#include "slam/scan_sequence.hpp"

namespace msislab {

/// One beam of the truth: its time (the sonar log's, as the readings carry it) and the range at
/// which its axis first meets a surface, if it does within the sonar's range.
struct AxisTruth {
  double t_s = 0.0;
  std::optional<double> first_hit_range_m;
};

struct FootprintSample {
  double range_m = 0.0;  ///< as reported, from the head
  double incidence_rad = 0.0;
  double offset_m = 0.0;  ///< reported - the axis's first hit
};

/// The samples of a run's scans (built without a footprint table) against its beams' truth,
/// `beams` in time order. A reading whose beam the truth does not list (no beam within 1 ms), whose
/// axis meets nothing, or that lies on no line (`line`) gives none.
std::vector<FootprintSample> footprint_samples(const std::vector<PlacedScan>& scans,
                                               const std::vector<AxisTruth>& beams,
                                               const LineNormalConfig& line);

struct FootprintGrid {
  std::vector<double> ranges_m;        ///< the nodes, ascending; a sample goes to the nearest
  std::vector<double> incidences_rad;  ///< the nodes, ascending in [0, pi/2]
  /// A reading farther than this from its axis's first hit is of another surface than the one
  /// the axis meets (a second return, or the axis past an edge the beam still sees), not of this
  /// surface's footprint: left out.
  double max_abs_offset_m = 5.0;
  int min_samples = 20;  ///< a cell with fewer has no figure (NaN in the table)
};

struct FootprintEstimate {
  FootprintTable table;
  std::vector<int> samples;  ///< per cell, row-major as the table
  std::size_t left_out = 0;  ///< samples beyond max_abs_offset_m
};

/// The table of the samples' mean and standard deviation (n - 1) per cell.
FootprintEstimate estimate_footprint(const std::vector<FootprintSample>& samples,
                                     const FootprintGrid& grid);

}  // namespace msislab
