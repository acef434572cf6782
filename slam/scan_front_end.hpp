// The scan front end every scan-based back end shares (trajectory SLAM's two filters and the pose
// graph; docs/trajectory_slam.md). One step per scan, in the paper's order:
//   1. the scan's motion checked (a motion that is not finite enters as unknown_motion()), its
//      DVL velocity and finite points kept;
//   2. the back end's prediction (paper Eq. 2);
//   3. the compass reading, when there is one and compass updates are on, through the back end's
//      gated update;
//   4. the skip rule: a scan with no finite motion or fewer points than a match needs is not
//      matched;
//   5. association (Eq. 3-4): the past scans whose estimated centre lies within gamma, nearest
//      first (nearest_candidates);
//   6. the back end's match updates against them (spIC, validation, the iterated EKF; Eq. 5-10);
//   7. the back end's end of the step; the counts kept in SlamTotals.
// A back end answers steps 2, 3, 5 (its distances), 6 and 7 through the hooks below; the
// sequence and the counts are written once, here.
#pragma once

#include <Eigen/Core>
#include <cstddef>
#include <utility>
#include <vector>

#include "geometry/gaussian_pose.hpp"
#include "slam/scan_builder.hpp"
#include "slam/scan_front_end_config.hpp"
#include "slam/scan_slam.hpp"
#include "slam/scan_slam_records.hpp"

namespace msislab {

/// Association's candidates: (estimated distance between the scans' centres m, past scan index),
/// nearest first.
using ScanCandidates = std::vector<std::pair<double, std::size_t>>;

/// Data association (paper Eq. 3-4), shared by every back end: the past scans j <= k - min_scan_gap
/// (k the newest, points.size() - 1) whose distance to the newest lies below gamma and which
/// have enough points to match, nearest first, at most max_matches_per_scan, as (distance, j).
ScanCandidates nearest_candidates(const std::vector<double>& distances_m,
                                  const std::vector<std::vector<ScanPoint>>& points,
                                  const ScanFrontEndConfig& config);

class ScanFrontEnd : public ScanSlam {
 public:
  /// Adds a scan (its points in its own frame, its motion from the previous scan's frame) and
  /// closes the loops it finds: the step above. A scan with a non-finite motion is chained with
  /// a zero motion of very large covariance (the back end loses track instead of failing);
  /// non-finite points are dropped.
  SlamStepStats add_scan(const Scan& scan) final;
  const SlamTotals& totals() const final { return totals_; }

 protected:
  /// The association, matching and compass settings.
  virtual const ScanFrontEndConfig& front_end_config() const = 0;
  /// Step 2: the newest scan's pose predicted from the previous one and `motion` (the scan's, or
  /// unknown_motion()). velocities_ already holds the scan's velocity; points_ does not yet hold
  /// its points.
  virtual void predict_scan(const Scan& scan, const GaussianPose2& motion) = 0;
  /// Step 3: the update by the scan's compass reading (finite, with a positive sigma) behind the
  /// back end's gate; whether it was accepted.
  virtual bool update_compass_reading(const Scan& scan, SlamStepStats& stats) = 0;
  /// Step 5: the estimated distance of each past scan j < k to the newest scan k, m.
  virtual std::vector<double> newest_scan_distances_m() const = 0;
  /// Step 6: scan k matched against the candidates and the back end updated; the matches, and
  /// the matched and accepted counts, in `stats`.
  virtual void update_with_matches(std::size_t k, const ScanCandidates& candidates,
                                   const Scan& scan, SlamStepStats& stats) = 0;
  /// Step 7: the end of scan k's step, after its updates or its skip.
  virtual void finish_scan_step(std::size_t k, const Scan& scan) = 0;

  std::vector<std::vector<ScanPoint>> points_;  ///< each scan's finite points, in its frame
  std::vector<Eigen::Vector3d> velocities_;     ///< each scan's Scan::velocity_vehicle (the clock)
  SlamTotals totals_;
};

}  // namespace msislab
