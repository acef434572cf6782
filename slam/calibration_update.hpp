// Carrying a run's calibration estimates into the next run (docs/trajectory_slam.md, "Calibration
// states"): the dataset's calibration with what the back end estimated beyond it (compass
// deviation, sonar clock offset, range scale, DVL scale) folded in, as a calibration.yaml states
// them.
#pragma once

#include <optional>
#include <vector>

#include "geometry/calibration.hpp"
#include "slam/scan_slam_records.hpp"

namespace msislab {

/// `stated` with the estimates added to it: compass_deviation_cos_deg / _sin_deg to
/// mru.deviation_cos_deg / _sin_deg, clock_offset_s to sonar.time_offset_s; range_scale and
/// dvl_scale multiply sonar.range_scale and dvl.scale_factor. Nullopt when none was estimated.
std::optional<Calibration> calibration_with_estimates(
    const Calibration& stated, const std::vector<CalibrationEstimate>& estimates);

}  // namespace msislab
