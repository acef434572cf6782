// Scoring of beam segmentation against simulation truth (docs/front_end.md): how often a beam's
// readings find the first surface on its axis, miss it or land elsewhere.
#pragma once

#include <cstddef>
#include <optional>
#include <vector>

namespace msislab {

/// What the score needs from a beam's truth (truth/beams.csv).
struct SegmentationTruth {
  std::optional<double> first_hit_range_m;  ///< first surface on the beam axis; none in range
  bool strongest_multipath = false;         ///< the strongest echo came by a specular route
};

/// Counts and fractions over one set of beams. A fraction whose denominator is zero is NaN.
struct SegmentationScore {
  std::size_t beams = 0;                  ///< every beam
  std::size_t beams_with_hit = 0;         ///< beams whose truth has a first hit
  std::size_t beams_multipath = 0;        ///< of those, beams whose strongest echo is multipath
  std::size_t readings = 0;               ///< every reading of every beam
  double hit_fraction = 0.0;              ///< a reading within the tolerance of the first hit
  double miss_fraction = 0.0;             ///< no reading
  double wrong_fraction = 0.0;            ///< readings, none within the tolerance
  double false_detection_fraction = 0.0;  ///< of readings: off the first hit, or no first hit
  double hit_fraction_direct = 0.0;       ///< hit fraction where the strongest echo is direct
  double hit_fraction_multipath = 0.0;    ///< hit fraction where the strongest echo is multipath
  double hit_range_rms_m = 0.0;           ///< RMS of (nearest reading - first hit) over hits
};

/// Scores per-beam readings (ranges_m[i] belongs to truth[i]; same sizes) against the first hit,
/// with a reading counted on the first hit when |range - first hit| <= tolerance_m.
SegmentationScore score_segmentation(const std::vector<SegmentationTruth>& truth,
                                     const std::vector<std::vector<double>>& ranges_m,
                                     double tolerance_m = 0.3);

}  // namespace msislab
