#include "slam/trajectory_correction.hpp"

namespace msislab {

std::vector<StampedPose> correct_trajectory(const std::vector<StampedPose>& dead_reckoning,
                                            const std::vector<StampedPose>& dr_at_scans,
                                            const std::vector<GaussianPose2>& corrected_scans) {
  std::vector<StampedPose> out;
  out.reserve(dead_reckoning.size());
  std::size_t k = 0;  // the next scan
  for (const StampedPose& d : dead_reckoning) {
    while (k < dr_at_scans.size() && dr_at_scans[k].t_s <= d.t_s) ++k;
    if (k == 0) {
      out.push_back(d);
      continue;
    }
    const StampedPose& anchor = dr_at_scans[k - 1];
    const Pose2 since_scan = anchor.pose.mean.between(d.pose.mean);
    out.push_back(
        {d.t_s, {corrected_scans[k - 1].mean.compose(since_scan), corrected_scans[k - 1].cov}});
  }
  return out;
}

}  // namespace msislab
