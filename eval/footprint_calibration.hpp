// The beam's footprint measured against a simulation's truth (docs/scan_matching.md, "The beam's
// footprint"): for every reading of a scan that lies on a line, its range, the incidence its
// scan shows (the angle between its beam's axis and the line's normal) and its offset, the range
// reported less the range at which the beam's axis first meets a surface (truth/beams.csv);
// then, per cell of a grid of range and incidence, the offsets' mean and standard deviation:
// the table slam/beam_footprint.hpp corrects scans with.
#pragma once

#include <limits>
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
  std::optional<double> strongest_range_m;  ///< the strongest noise-free echo's range
  /// The horizontal angle from the axis to that echo's source (truth/beams.csv).
  std::optional<double> strongest_bearing_offset_rad;
};

struct FootprintSample {
  double range_m = 0.0;  ///< as reported, from the head
  double incidence_rad = 0.0;
  double offset_m = 0.0;  ///< reported - the axis's first hit
  /// The strongest echo's source off the axis, positive toward the line's normal (toward lower
  /// incidence); NaN when the truth has no bearing or the reading is not that echo.
  double bearing_toward_normal_rad = std::numeric_limits<double>::quiet_NaN();
};

/// The samples of a run's scans (built without a footprint table) against its beams' truth,
/// `beams` in time order. A reading whose beam the truth does not list (no beam within 1 ms), whose
/// axis meets nothing, or that lies on no line (`line`) gives none.
std::vector<FootprintSample> footprint_samples(const std::vector<PlacedScan>& scans,
                                               const std::vector<AxisTruth>& beams,
                                               const LineNormalConfig& line);

/// How far a reading's range may lie from its beam's strongest noise-free echo for the reading to
/// be that echo (and its source's bearing to be the reading's), m.
inline constexpr double kSameEchoRange_m = 1.0;

/// The bearing of a run's readings against truth: for every reading (on a line or not) whose range
/// lies within max_range_gap_m of its beam's strongest noise-free echo, the angle from its beam's
/// axis to that echo's source (truth/beams.csv's strongest_bearing_offset_rad). The reading is
/// drawn on the axis, so this is its bearing error: the spread a scan point's bearing sigma
/// stands for (docs/scan_matching.md, "The bearing spread"). `beams` in time order.
std::vector<double> bearing_offsets_rad(const std::vector<PlacedScan>& scans,
                                        const std::vector<AxisTruth>& beams,
                                        double max_range_gap_m = kSameEchoRange_m);

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
  /// Per incidence node (over every range): the mean and the root mean square of the samples'
  /// bearing toward the normal, and how many had one (NaN under min_samples).
  std::vector<double> bearing_toward_normal_mean_rad;
  std::vector<double> bearing_toward_normal_rms_rad;
  std::vector<int> bearing_samples;
};

/// The table of the samples' mean and standard deviation (n - 1) per cell.
FootprintEstimate estimate_footprint(const std::vector<FootprintSample>& samples,
                                     const FootprintGrid& grid);

}  // namespace msislab
