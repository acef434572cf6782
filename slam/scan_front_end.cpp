#include "slam/scan_front_end.hpp"

#include <algorithm>
#include <cmath>

namespace msislab {

ScanCandidates nearest_candidates(const std::vector<double>& distances_m,
                                  const std::vector<std::vector<ScanPoint>>& points,
                                  const ScanFrontEndConfig& config) {
  const std::size_t k = points.size() - 1;
  std::vector<std::pair<double, std::size_t>> candidates;
  for (std::size_t j = 0; j + static_cast<std::size_t>(config.min_scan_gap) <= k; ++j) {
    if (distances_m[j] < config.association_distance_m &&
        static_cast<int>(points[j].size()) >= config.matching.min_inliers) {
      candidates.emplace_back(distances_m[j], j);
    }
  }
  std::sort(candidates.begin(), candidates.end());
  if (static_cast<int>(candidates.size()) > config.max_matches_per_scan) {
    candidates.resize(static_cast<std::size_t>(config.max_matches_per_scan));
  }
  return candidates;
}

SlamStepStats ScanFrontEnd::add_scan(const Scan& scan) {
  const ScanFrontEndConfig& config = front_end_config();
  SlamStepStats stats;
  const bool motion_ok = scan.motion.mean.vector().allFinite() && scan.motion.cov.allFinite();
  velocities_.push_back(scan.velocity_vehicle.allFinite() ? scan.velocity_vehicle
                                                          : Eigen::Vector3d::Zero());
  predict_scan(scan, motion_ok ? scan.motion : unknown_motion());
  points_.push_back(finite_points(scan.points));
  ++totals_.scans;
  const std::size_t k = points_.size() - 1;

  if (config.compass_updates && std::isfinite(scan.compass_yaw_world_rad) &&
      scan.compass_sigma_rad > 0.0) {
    stats.compass_accepted = update_compass_reading(scan, stats);
    totals_.compass_accepted += stats.compass_accepted;
  }
  if (!motion_ok || static_cast<int>(points_[k].size()) < config.matching.min_inliers) {
    stats.skipped = true;
    ++totals_.skipped;
  } else {
    const ScanCandidates candidates =
        nearest_candidates(newest_scan_distances_m(), points_, config);
    stats.candidates = static_cast<int>(candidates.size());
    update_with_matches(k, candidates, scan, stats);
    totals_.candidates += stats.candidates;
    totals_.matched += stats.matched;
    totals_.accepted += stats.accepted;
  }
  finish_scan_step(k, scan);
  return stats;
}

}  // namespace msislab
