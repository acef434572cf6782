// What every scan-based SLAM back end offers its caller (the paper's two filters, the pose graph,
// or a user's own): scans in, each step's matches and counts out, and the scans' world poses with
// their covariances. run_scan_slam (slam/scan_slam_pipeline) drives any of them the same way.
#pragma once

#include <Eigen/Core>
#include <cmath>
#include <cstddef>
#include <optional>
#include <vector>

#include "geometry/gaussian_pose.hpp"
#include "slam/scan_builder.hpp"
#include "slam/scan_slam_records.hpp"

namespace msislab {

/// A motion whose covariance says "unknown" (100 m and pi rad standard deviation): what a back
/// end chains for a scan whose motion is not finite, losing track instead of failing.
inline GaussianPose2 unknown_motion() {
  return {Pose2(), Eigen::Vector3d(1e4, 1e4, M_PI * M_PI).asDiagonal()};
}

/// The scan's points with finite coordinates and covariances.
inline std::vector<ScanPoint> finite_points(const std::vector<ScanPoint>& points) {
  std::vector<ScanPoint> finite;
  finite.reserve(points.size());
  for (const ScanPoint& p : points) {
    if (p.p_m.allFinite() && p.cov.allFinite()) finite.push_back(p);
  }
  return finite;
}

class ScanSlam {
 public:
  virtual ~ScanSlam() = default;
  /// Adds a scan (its points in its own frame, its motion from the previous scan's frame) and
  /// closes the loops it finds.
  virtual SlamStepStats add_scan(const Scan& scan) = 0;
  /// Ends the run after the last scan: a back end that smooths (the pose graph) solves once
  /// more, so that scan_pose_world gives its final estimate; nothing for the filters. A scan
  /// added afterwards continues the run, and the next finish ends it again.
  virtual void finish() {}
  virtual std::size_t scans() const = 0;
  virtual const SlamTotals& totals() const = 0;
  /// The world pose of scan i with its covariance, as known after the last scan (for the
  /// filters, their final estimate of the whole trajectory; for the pose graph, its smoothed
  /// solution, after finish()).
  virtual GaussianPose2 scan_pose_world(std::size_t i) const = 0;
  /// The world pose of each scan as it was known when that scan was added (the online
  /// estimate), where the back end tells it apart from scan_pose_world; nullopt for the filters,
  /// whose trajectory is written from their final estimate.
  virtual std::optional<std::vector<GaussianPose2>> online_poses() const { return std::nullopt; }
  /// Matches a robust back end set aside (beyond its gate at its last solution); nullopt for
  /// the filters, whose gate rejects before the update.
  virtual std::optional<int> matches_downweighted() const { return std::nullopt; }
  /// The calibration parameters the back end estimates (none by default).
  virtual std::vector<CalibrationEstimate> calibration() const { return {}; }
  /// Whether the back end carries the DVL's scale factor as a state (its scan motions must then
  /// leave out the dead reckoning's considered scale uncertainty, which the state replaces).
  virtual bool estimates_dvl_scale() const { return false; }
};

}  // namespace msislab
