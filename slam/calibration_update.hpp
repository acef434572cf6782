// Carrying a run's calibration estimates into the next run (docs/trajectory_slam.md, "Calibration
// states"): the dataset's calibration with the compass deviation and the sonar clock offset that
// the back end estimated beyond it added in, as a calibration.yaml states them.
#pragma once

#include <optional>
#include <vector>

#include "geometry/calibration.hpp"
#include "slam/scan_slam_records.hpp"

namespace msislab {

/// `stated` with the estimates that calibration.yaml has keys for added to it:
/// compass_deviation_cos_deg / _sin_deg to mru.deviation_cos_deg / _sin_deg, clock_offset_s to
/// sonar.time_offset_s. Nullopt when none of those was estimated (the range and DVL scales have no
/// calibration.yaml key).
std::optional<Calibration> calibration_with_estimates(
    const Calibration& stated, const std::vector<CalibrationEstimate>& estimates);

}  // namespace msislab
