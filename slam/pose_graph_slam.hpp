// Pose-graph SLAM: the paper's front end (the same scans, candidate selection by
// distance, spIC matches and their validation as trajectory SLAM) on a Ceres pose graph
// (slam/pose_graph) instead of a filter. Node 0 is the start pose (a prior with its covariance: the
// compass informs it too, where the filters hold the start's mean fixed and add its covariance to
// their output); node i + 1 is scan i's centre in the world. Each scan adds:
//   - its dead-reckoning motion from the previous scan as an edge (not robust), with its
//     covariance;
//   - the compass heading as a heading edge (trajectory_slam.compass_updates), behind the filters'
//     compass gate;
//   - each validated match passing the innovation gate as a robust edge.
// Each match starts, as in the filters, from what the back end knows of the relative pose: the
// joint marginal of the two nodes in the graph (one factorisation of the graph's information per
// scan, over the newest node and its candidates), updated by the compass and by each accepted
// match of the scan with the filters' iterated EKF on that small joint. Every edge the scan adds
// involves only these nodes, so the small update gives their marginal in the grown graph to first
// order without solving the graph for each match; the newest node's covariance from it is the
// online covariance.
// The graph is solved every `solve_every` scans, warm-started from the last solution (the updated
// means of the scan's nodes); each scan's pose then is the online estimate (online_poses). The last
// scan triggers nothing special: scan_pose_world solves once more and gives the smoothed
// trajectory.
#pragma once

#include <memory>
#include <optional>
#include <vector>

#include "slam/pose_graph.hpp"
#include "slam/trajectory_slam.hpp"

namespace msislab {

struct PoseGraphSlamConfig {
  PoseGraphConfig graph;
  int solve_every = 1;  ///< solve after every k-th scan (and for the smoothed trajectory)
};

class PoseGraphSlam : public ScanSlam {
 public:
  /// front_end: the candidate selection, gates, spIC and validation of trajectory SLAM (its
  /// filter-only keys, such as iekf_iterations, are not used).
  PoseGraphSlam(const TrajectorySlamConfig& front_end, const PoseGraphSlamConfig& config,
                const GaussianPose2& start_world);

  SlamStepStats add_scan(const Scan& scan) override;
  std::size_t scans() const override { return motions_.size(); }
  const SlamTotals& totals() const override { return totals_; }
  /// The smoothed solution: the graph solved after the last scan, marginal covariances.
  GaussianPose2 scan_pose_world(std::size_t i) const override;
  std::optional<std::vector<GaussianPose2>> online_poses() const override { return online_; }
  /// Matches the robust loss set aside at the last solve (beyond the gate there).
  std::optional<int> matches_downweighted() const override { return downweighted_; }

 private:
  /// Solves the graph (const: the smoothed solution is a cache of the same graph, and solving
  /// a solved graph leaves it where it is).
  void solve() const;
  /// The compass on the newest node (its belief `newest`, updated in place) behind the filters'
  /// gate; adds the heading edge when it passes.
  bool update_compass(std::size_t node, double yaw_world_rad, double sigma_rad,
                      GaussianPose2& newest);
  /// Matches scan k against the candidates, adds the accepted matches as edges, and returns
  /// the newest node's belief after them.
  GaussianPose2 match(std::size_t k, const std::vector<std::pair<double, std::size_t>>& candidates,
                      SlamStepStats& stats);
  /// The final solve and every scan's covariance, once after the last add_scan.
  void smooth() const;

  TrajectorySlamConfig front_end_;
  PoseGraphSlamConfig config_;
  std::unique_ptr<PoseGraph> graph_;
  Eigen::Matrix3d start_cov_;           ///< node 0's covariance (zero when it is held fixed)
  std::vector<GaussianPose2> motions_;  ///< motions_[i]: scan i from scan i-1 (or the start)
  std::vector<std::vector<ScanPoint>> points_;
  std::vector<GaussianPose2> online_;
  SlamTotals totals_;
  mutable int downweighted_ = 0;
  mutable std::vector<GaussianPose2> smoothed_;  ///< filled by smooth(); cleared by add_scan
};

}  // namespace msislab
