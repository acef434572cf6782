// The sonar statistics that compare a simulated dataset with the real one (docs/fidelity.md),
// computed from the detections and the beam times alone, so the same code runs on both sides:
// detected bins, runs and first ranges per beam, range distributions, readings per revolution and
// the rotation of the head. The detections are grouped and checked by io/detected_beams.
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

#include "slam/scan_sequence.hpp"

namespace msislab {

/// Share (0..1) of the values in each band [k band_m, (k + 1) band_m), k = 0 .. bands - 1; the
/// top edge bands x band_m belongs to the last band. Values outside [0, bands x band_m] are in no
/// band. All zero for an empty sample.
std::vector<double> band_shares(const std::vector<double>& values_m, double band_m, int bands);

/// Runs in a beam's detected bins: each range is bin round(range / bin_m), and a gap of one
/// missing bin or more starts a new run (a bin detected twice is one bin). 0 without bins.
int count_runs(const std::vector<double>& ranges_m, double bin_m);

/// Length of the nearest run of a beam's detected bins (bins as in count_runs), in metres:
/// (last bin - first bin + 1) x bin_m. 0 without bins.
double first_run_length_m(const std::vector<double>& ranges_m, double bin_m);

/// Incidence bands of the echo-extent statistic: [0, 15), [15, 30), ... [60, 75) deg.
constexpr int kIncidenceBands = 5;
constexpr double kIncidenceBand_deg = 15.0;

/// Incidence of the beam on the surface it saw (deg from the surface normal), from the first
/// ranges r_before, r_after of the beams either side (angle_step_rad apart each) and its own r:
/// atan(|r_after - r_before| / (r x 2 angle_step_rad)). NaN when a neighbour is more than
/// max_jump_m away from r (another surface, an edge) or r is not positive.
double incidence_from_neighbours_deg(double r_before_m, double r_m, double r_after_m,
                                     double angle_step_rad, double max_jump_m = 3.0);

/// One beam with detected bins.
struct DetectedBeam {
  std::int64_t beam_row = 0;     ///< 0-based row in *_IS_timestamps.log
  std::int32_t keyframe = 0;     ///< the revolution it belongs to
  std::int32_t angle_idx = 0;    ///< transducer step
  double angle_rad = 0.0;        ///< transducer angle
  std::vector<double> ranges_m;  ///< its detected bins, in file order
};

/// The samples behind the per-beam statistics. Counted beams: every beam of the keyframes from the
/// first to the last one in the file, beams_per_revolution per keyframe (a beam without detected
/// bins is empty); beams outside every keyframe are not counted.
struct SonarStatistics {
  int keyframes = 0;
  std::size_t beams = 0;                    ///< counted beams
  std::size_t empty_beams = 0;              ///< counted beams without a detected bin
  std::vector<double> bins_per_beam;        ///< every counted beam, empty ones included
  std::vector<double> runs_per_beam;        ///< every counted beam, empty ones included
  std::vector<double> first_ranges_m;       ///< the smallest detected range of each non-empty beam
  std::vector<double> detected_ranges_m;    ///< every detected bin
  std::vector<double> beams_per_360;        ///< beam rows between one angle step's beams in
                                            ///< consecutive keyframes
  std::vector<double> revolution_period_s;  ///< the beam times between the same two beams
  std::vector<double> readings_per_revolution;  ///< per keyframe, see readings_per_keyframe
  /// The nearest run's length of every beam whose two neighbouring beam rows (same keyframe) have
  /// detections, by the incidence incidence_from_neighbours_deg gives it (kIncidenceBands bands
  /// of kIncidenceBand_deg; steeper beams are in none): how an echo smears over an oblique wall.
  std::vector<std::vector<double>> run_length_by_incidence_m =
      std::vector<std::vector<double>>(kIncidenceBands);
};

/// beam_times_s: the time of every beam row (*_IS_timestamps.log); beams from group_detections;
/// angle_step_rad: the head's step between consecutive beams.
SonarStatistics sonar_statistics(const std::vector<DetectedBeam>& beams,
                                 const std::vector<double>& beam_times_s, int beams_per_revolution,
                                 double bin_m, double angle_step_rad);

/// Readings per keyframe, from the first to the last keyframe of beams: the readings of each
/// beam's row (readings is indexed by beam row, as load_sonar_readings returns it) summed over the
/// keyframe's beams.
std::vector<double> readings_per_keyframe(const std::vector<DetectedBeam>& beams,
                                          const std::vector<BeamReadings>& readings);

}  // namespace msislab
