// From corrected scan poses back to a full-rate trajectory: between scan frames the vehicle moves
// as dead reckoning says, anchored at the latest corrected scan pose.
#pragma once

#include <vector>

#include "geometry/gaussian_pose.hpp"

namespace msislab {

/// For every dead-reckoning sample at time t with the latest scan k at or before t:
/// pose(t) = S_k (+) ((-)D_k (+) D(t)), with S_k the corrected scan pose and D_k the dead-reckoning
/// pose at scan k's time; before the first scan the dead reckoning is kept. Each pose carries the
/// covariance of its anchoring scan (the motion since it is not added).
std::vector<StampedPose> correct_trajectory(const std::vector<StampedPose>& dead_reckoning,
                                            const std::vector<StampedPose>& dr_at_scans,
                                            const std::vector<GaussianPose2>& corrected_scans);

}  // namespace msislab
