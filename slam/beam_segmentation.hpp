// Beam segmentation: from one sonar beam (an echo intensity profile, or the bins a detector already
// marked) to the range(s) of the surfaces it saw, each with its uncertainty (paper Sec. II-A;
// Burguera et al. ETFA 2010, Mallios et al.; docs/front_end.md).
#pragma once

#include <cstdint>
#include <string>
#include <vector>

namespace msislab {

enum class SegmentationMethod {
  kMaxIntensity,     ///< the strongest bin beyond the minimum range, if above the threshold
  kThresholdGroups,  ///< runs of bins above the threshold; the strongest bin of each run
  kSmoothedFirst,    ///< smoothed profile; the peak of the first run above the threshold
};

/// Which sonar data of a dataset the front end reads when it has both.
enum class SonarSource {
  kAuto,        ///< the raw profiles (*_IS.log) when present, else the detections
  kRaw,         ///< the raw profiles only
  kDetections,  ///< the detected bins (*_detections.csv[.gz]) only, as the real St. Pere data
};

struct SegmentationConfig {
  SonarSource source = SonarSource::kAuto;
  SegmentationMethod method = SegmentationMethod::kThresholdGroups;
  double min_range_m = 1.0;          ///< bins closer than this are ignored (ring-down, vehicle)
  double threshold = 100.0;          ///< intensity 0..255 a return must reach
  int max_ranges_per_beam = 1;       ///< kThresholdGroups: the nearest N runs are kept
  int min_run_bins = 1;              ///< runs shorter than this are noise
  int smoothing_bins = 3;            ///< kSmoothedFirst: moving-average window (odd)
  double sigma_range_m = 0.1;        ///< range standard deviation of a reading
  double sigma_bearing_rad = 0.026;  ///< bearing standard deviation (about half the 3 deg beam)
};

/// One range extracted from a beam.
struct SonarReading {
  double t_s = 0.0;
  double range_m = 0.0;
  double bearing_vehicle_rad = 0.0;  ///< in the vehicle frame (calibration applied)
  double sigma_range_m = 0.0;
  double sigma_bearing_rad = 0.0;
};

/// Ranges (m, nearest first) found in an intensity profile whose bin j lies at (j + 1) x bin_m.
std::vector<double> segment_profile(const std::vector<std::uint8_t>& intensity, double bin_m,
                                    const SegmentationConfig& config);

/// Ranges (m, nearest first) chosen from a beam's detected bins (the St. Pere detections file:
/// bins a detector marked, no intensities): runs of adjacent bins (gaps of at most one bin) form
/// one return, each reported at its centre; the nearest max_ranges_per_beam beyond min_range_m
/// are kept.
std::vector<double> segment_detections(const std::vector<double>& detected_ranges_m, double bin_m,
                                       const SegmentationConfig& config);

/// "max_intensity", "threshold_groups", "smoothed_first".
std::string to_string(SegmentationMethod method);
/// Inverse of to_string; false for an unknown name.
bool parse_segmentation_method(const std::string& name, SegmentationMethod& method);

}  // namespace msislab
