// Relative pose error over a travelled distance (docs/cli.md, msislab eval): how far the estimate's
// motion between two times strays from the truth's, whatever frame the estimate is in.
#pragma once

#include <cstddef>
#include <vector>

#include "geometry/gaussian_pose.hpp"

namespace msislab {

/// Mean, RMSE, median and maximum of a sample, in the unit of the member that holds them.
struct SampleSummary {
  double mean = 0.0;
  double rmse = 0.0;
  double median = 0.0;
  double max = 0.0;
};

/// The samples are the truth stamps inside the estimate's time span, the estimate interpolated at
/// each. A pair (i, j) joins each sample i to the first later sample j whose truth path length
/// from i (the straight steps between consecutive samples, summed) reaches delta_m. Its error is
///   E_ij = (T_est_i^-1 T_est_j)^-1 (T_true_i^-1 T_true_j),
/// translational |t(E_ij)| and rotational |yaw(E_ij)|. A rigid motion of the whole estimate
/// cancels in T_est_i^-1 T_est_j, so an alignment does not change it.
struct RelativePoseError {
  double delta_m = 0.0;
  std::size_t pairs = 0;
  SampleSummary translation_m;  ///< |t(E_ij)|; zeros when there is no pair
  SampleSummary rotation_deg;   ///< |yaw(E_ij)|; zeros when there is no pair
};

/// The RPE of the estimate against pose truth (time-ordered, non-empty estimate). Requires
/// delta_m > 0.
RelativePoseError relative_pose_error(const std::vector<StampedPose>& estimate,
                                      const std::vector<StampedPose>& truth, double delta_m);

}  // namespace msislab
