// The detector that made the St. Pere detections file (../shared/datasets/stpere/README.md): an
// echo intensity profile in, the bins it marks as detected out. The real data have only these
// marks, so the simulator runs the same detector on its profiles and every statistic and every
// pipeline stage after it sees both datasets the same way (docs/front_end.md).
#pragma once

#include <cstdint>
#include <vector>

namespace msislab {

struct DetectionModelConfig {
  int smoothing_bins = 5;    ///< centred moving-mean window, bins (odd; the README does not say)
  double ramp_max = 30.0;    ///< intensity subtracted at the last bin; 0 at the first, linear
  double threshold = 45.0;   ///< a bin is detected when smoothed minus ramp exceeds this
  double min_range_m = 1.0;  ///< bins closer than this are dropped
};

/// Indices j of the detected bins of a profile whose bin j lies at (j + 1) x bin_m, ascending:
///   s_j = mean of intensity over the window centred on j (shrunk at the profile's ends),
///   ramp_j = ramp_max x j / (N - 1),
///   detected  <=>  s_j - ramp_j > threshold  and  (j + 1) x bin_m >= min_range_m.
std::vector<int> detect_bins(const std::vector<std::uint8_t>& intensity, double bin_m,
                             const DetectionModelConfig& config);

}  // namespace msislab
