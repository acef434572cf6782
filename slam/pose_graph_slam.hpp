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
// Windowed (online_window_scans = W > 0), for long missions: the joint covariance of the newest W
// nodes is kept from scan to scan instead of factoring the whole graph's information each scan;
// each scan composes its node onto it, updates it by its compass and matches and drops the nodes
// that fall out of the window (marginalising them: their rows and columns go). While a scan's
// candidates lie in the window this is the same first-order marginal. A candidate older than the
// window (an old node) joins as the nearest node of the belief composed with the odometry between
// them when that is at most online_old_chain_scans away, else with its last marginal,
// uncorrelated with the window (the one approximation left, counted by
// old_nodes_uncorrelated); the online_old_nodes most recently matched old nodes then stay in the
// joint, so a later match updates them rather than adding their marginal again. The online solves
// hold the nodes older than the window (the old nodes in the belief where its updates put them);
// the smoothing solve frees them all.
#pragma once

#include <array>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "slam/pose_graph.hpp"
#include "slam/pose_graph_belief.hpp"
#include "slam/trajectory_slam.hpp"

namespace msislab {

struct PoseGraphSlamConfig {
  PoseGraphConfig graph;
  int solve_every = 1;  ///< solve after every k-th scan (and for the smoothed trajectory)
  /// The online window, in scans: 0, the whole graph (each scan's belief from the whole graph's
  /// information, each solve over every node); W > 0, the newest W nodes (their joint
  /// covariance kept by the EKF, older nodes held in the online solves), so that a step's cost
  /// does not grow with the mission (docs/pose_graph.md, "Long missions").
  int online_window_scans = 0;
  /// Windowed: how many old nodes (older than the window) stay in the window's joint after a
  /// match, the most recently matched first, so that later matches update their marginal and
  /// their correlation with the window instead of adding their old marginal again.
  int online_old_nodes = 30;
  /// Windowed: an old node that joins the belief within this many scans (along the odometry
  /// chain) of a node already in it joins as that node composed with the odometry between them,
  /// correlated with the belief; farther, with its last marginal, uncorrelated. 0: always the
  /// latter.
  int online_old_chain_scans = 10;
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
  /// The calibration switched on in trajectory_slam.calibration that the graph estimates: the
  /// range scale and the DVL's (after the smoothing solve, scan_pose_world, the smoothed graph's
  /// values with the whole graph's standard deviations; before, the online solution's with the
  /// belief's), the compass's bias at the newest scan (the graph's solution there, the belief's
  /// standard deviation).
  std::vector<CalibrationEstimate> calibration() const override;
  /// With trajectory_slam.calibration.dvl_scale: the odometry edges read the DVL's scale block.
  bool estimates_dvl_scale() const override;
  /// Windowed: the candidates so far that were older than the window.
  int matches_outside_window() const { return outside_window_matches_; }
  /// Windowed: the old nodes that joined the belief uncorrelated with it (no node of the belief
  /// within online_old_chain_scans of them).
  int old_nodes_uncorrelated() const { return old_uncorrelated_; }

 private:
  /// The newest node's belief after the odometry edge to it (Eq. 2): alone, with the calibration,
  /// or windowed in the joint of the kept old nodes and the window.
  PoseGraphBelief odometry_belief(std::size_t node, const GaussianPose2& motion);
  /// Associates scan k with the past scans (Eq. 3-4) and matches it against them.
  void associate_and_match(std::size_t k, PoseGraphBelief& belief, SlamStepStats& stats);
  /// The end of scan k's step: the window or the calibration's joint kept, the online solve, the
  /// newest pose and the calibration's estimates recorded.
  void finish_scan(std::size_t k, double t_s, const PoseGraphBelief& belief);
  /// Solves the graph (const: the smoothed solution is a cache of the same graph, and solving
  /// a solved graph leaves it where it is); count_downweighted as PoseGraph::solve.
  void solve(bool count_downweighted) const;
  /// The compass on the newest node (its belief `newest`, updated in place) behind the filters'
  /// gate; adds the heading edge when it passes.
  bool update_compass(double yaw_world_rad, double sigma_rad, PoseGraphBelief& belief);
  /// Matches scan k against the candidates (candidate c at index in_belief[c] of the belief),
  /// adds the accepted matches as edges and updates the belief by each.
  void match(std::size_t k, const std::vector<std::pair<double, std::size_t>>& candidates,
             const std::vector<Eigen::Index>& in_belief, PoseGraphBelief& belief,
             SlamStepStats& stats);
  /// The final solve and every scan's covariance, once after the last add_scan.
  void smooth() const;
  /// The scan's nodes as the whole graph knows them: the candidates' (in their order), then the
  /// newest's (newest_mean, with the covariance from the graph's information).
  PoseGraphBelief whole_graph_belief(std::size_t node, const Pose2& newest_mean,
                                     const std::vector<std::pair<double, std::size_t>>& candidates);
  /// Windowed (online_window_scans > 0): the candidates' indices in the belief (the kept old
  /// nodes, the window, the newest node), an old candidate not in it appended (append_old); k,
  /// the scan, marks the old ones used.
  std::vector<Eigen::Index> append_outside_window(
      PoseGraphBelief& belief, const std::vector<std::pair<double, std::size_t>>& candidates,
      std::size_t k);
  /// Windowed: appends old node i to the belief, composed from the nearest node of the belief
  /// along the odometry (online_old_chain_scans), or with its last marginal, uncorrelated.
  void append_old(PoseGraphBelief& belief, std::size_t i);
  /// Windowed, with the odometry through the calibration: appends old node i composed from the
  /// belief's node at `from` along the odometry, correlated with the calibration.
  void append_old_through_calibration(PoseGraphBelief& belief, std::size_t i, Eigen::Index from);
  /// Windowed: keeps the window's part of the belief and the online_old_nodes most recently used
  /// old nodes (k, the scan, for this scan's), dropping (marginalising) the others with their
  /// marginal stored, and holds the nodes older than the window in the graph's online solves.
  void keep_window(const PoseGraphBelief& belief, std::size_t k);
  /// Windowed: the belief's indices of the old nodes kept (in the belief's order) and
  /// old_nodes_, old_used_ set to them; those dropped leave their marginal in left_window_cov_.
  std::vector<Eigen::Index> keep_old_nodes(const PoseGraphBelief& belief, std::size_t k);
  /// Writes the belief's means to the graph: the next solve's warm start, and where the old
  /// nodes of a windowed belief are held in the online solves (as the whole graph's candidates
  /// start its solves from their updated means).
  void write_means(const PoseGraphBelief& belief);
  bool estimates_heading_bias() const;
  bool estimates_range_scale() const;
  /// The graph's constants switched on, in GraphConstant order (the range scale, the DVL's, the
  /// clock offset, the deviation's a and b).
  std::vector<GraphConstant> estimated_constants() const;
  /// A constant's index in the belief's parameters (after the heading bias, in that order).
  Eigen::Index constant_at(GraphConstant which) const;
  /// The odometry edge in the belief (Eq. 2): node `node` appended as the previous one composed
  /// with the motion, through the DVL's scale and the compass's deviation when estimated; it
  /// becomes the newest.
  void append_odometry(PoseGraphBelief& belief, std::size_t node, Eigen::Index previous,
                       const GaussianPose2& motion) const;
  /// Whether the motion to scan node `node` starts from a heading the compass's deviation is in:
  /// always but from an exact start (node 0 held fixed).
  bool start_deviated(std::size_t node) const;
  /// The odometry goes through the calibration (the DVL's scale or the deviation estimated).
  bool calibrates_odometry() const;
  /// The DVL scale's and the deviation's a's index in the belief's parameters; -1: not estimated.
  Eigen::Index odometry_k_at() const;
  Eigen::Index odometry_ab_at() const;
  /// The true motion to node node_to behind a measured one (slam/calibration_model.hpp), at the
  /// calibration `parameters` (the belief's) and the motion's two headings.
  CalibratedMotion calibrated_step(const Eigen::VectorXd& parameters, const Pose2& motion,
                                   double psi_from_rad, double psi_to_rad,
                                   std::size_t node_to) const;
  /// The belief's parameters as the graph holds them: the heading bias of node bias_of's block
  /// (none: 0, before the first scan's), the range scale.
  Eigen::VectorXd graph_parameters(std::optional<std::size_t> bias_of) const;
  /// What a match of the newest node against the belief's node c observes: its pose seen from c,
  /// through the range scale when estimated, with H and H P H^T.
  GaussianPose2 predict_match(const PoseGraphBelief& belief, Eigen::Index c,
                              Eigen::MatrixXd* H) const;
  /// The node whose bias block scan node `node` reads the compass through: its own when the bias
  /// walks, else the first scan's (a constant).
  std::size_t bias_node(std::size_t node) const;
  /// The bias block of scan node `node` at time t_s: the prior at the first scan, the walk from
  /// the previous one after (the belief's bias variance grown by it).
  void add_bias_block(std::size_t node, double t_s, PoseGraphBelief& belief);

  TrajectorySlamConfig front_end_;
  PoseGraphSlamConfig config_;
  std::unique_ptr<PoseGraph> graph_;
  Eigen::Matrix3d start_cov_;           ///< node 0's covariance (zero when it is held fixed)
  std::vector<GaussianPose2> motions_;  ///< motions_[i]: scan i from scan i-1 (or the start)
  std::vector<std::vector<ScanPoint>> points_;
  std::vector<GaussianPose2> online_;
  /// Windowed: the joint covariance of the kept old nodes and nodes window_first_.. (the newest
  /// last), and each old node's marginal from when it left the window or the kept old nodes.
  std::size_t window_first_ = 0;
  Eigen::MatrixXd window_cov_;
  std::vector<Eigen::Matrix3d> left_window_cov_;
  /// Windowed: the old nodes kept (first in window_cov_'s order), and the scan that last matched
  /// each (the scan's index k).
  std::vector<std::size_t> old_nodes_, old_used_;
  int old_uncorrelated_ = 0;
  SlamTotals totals_;
  mutable int downweighted_ = 0;
  int outside_window_matches_ = 0;               ///< candidates older than the window (windowed)
  mutable std::vector<GaussianPose2> smoothed_;  ///< filled by smooth(); cleared by add_scan
  /// With the heading bias, whole-graph mode: the joint of the bias and the newest node.
  Eigen::MatrixXd newest_joint_;
  double previous_t_s_ = 0.0;                 ///< the last scan's time (the bias's walk)
  std::pair<double, double> bias_{0.0, 0.0};  ///< the newest bias and its sd, rad
  /// Per GraphConstant: online, the constant and its sd; after smooth(), the smoothed graph's.
  std::array<std::pair<double, double>, 5> constant_estimates_{};
  mutable std::array<std::pair<double, double>, 5> smoothed_constants_{};
  std::vector<Eigen::Vector3d> velocities_;  ///< each scan's Scan::velocity_vehicle (the clock)
};

}  // namespace msislab
