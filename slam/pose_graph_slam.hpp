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
// means of the scan's nodes); each scan's pose then is the online estimate (online_poses). After
// the last scan, finish() solves once more, the whole graph with its robust loss, and
// scan_pose_world gives that smoothed trajectory. What the step's belief starts from is kept from
// scan to scan by one of two strategies (slam/pose_graph_online.hpp): the whole graph's
// information factored every scan (WholeGraphOnline), or for long missions
// (online_window_scans = W > 0) the joint covariance of the newest W nodes kept by the EKF, the
// online solves holding the nodes older than the window (WindowedOnline).
#pragma once

#include <array>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "slam/pose_graph.hpp"
#include "slam/pose_graph_belief.hpp"
#include "slam/pose_graph_calibration.hpp"
#include "slam/pose_graph_online.hpp"
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

class PoseGraphSlam : public ScanFrontEnd {
 public:
  /// front_end: the step every scan back end shares (candidates, spIC, validation, gates, how a
  /// step's updates are made); calibration: the states the graph estimates beside the poses.
  PoseGraphSlam(const ScanFrontEndConfig& front_end, const CalibrationStatesConfig& calibration,
                const PoseGraphSlamConfig& config, const GaussianPose2& start_world);
  // The online belief and the calibration hold references into this object.
  PoseGraphSlam(const PoseGraphSlam&) = delete;
  PoseGraphSlam& operator=(const PoseGraphSlam&) = delete;

  /// The smoothing solve: the whole graph solved after the last scan (constants freed, the loss's
  /// set-aside edges counted) and every scan's marginal covariance.
  void finish() override;
  std::size_t scans() const override { return motions_.size(); }
  /// The smoothed solution of finish(); std::logic_error when a scan came after the last finish.
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
  bool estimates_dvl_scale() const override { return calibration_.estimates_dvl_scale(); }
  /// Windowed: the candidates so far that were older than the window.
  int matches_outside_window() const { return online_belief_->matches_outside_window(); }
  /// Windowed: the old nodes that joined the belief uncorrelated with it (no node of the belief
  /// within online_old_chain_scans of them).
  int old_nodes_uncorrelated() const { return online_belief_->old_nodes_uncorrelated(); }

 private:
  // The front end's steps (slam/scan_front_end.hpp), on step_belief_.
  const ScanFrontEndConfig& front_end_config() const override { return front_end_; }
  /// The odometry edge to the new node and its belief (the online belief's).
  void predict_scan(const Scan& scan, const GaussianPose2& motion) override;
  /// The compass on the newest node behind the filters' gate, its heading edge when it passes.
  bool update_compass_reading(const Scan& scan, SlamStepStats& stats) override;
  std::vector<double> newest_scan_distances_m() const override;
  /// The candidates joined to the newest node's belief (by the online belief), then the matches.
  void update_with_matches(std::size_t k, const ScanCandidates& candidates, const Scan& scan,
                           SlamStepStats& stats) override;
  /// The end of scan k's step: the online belief kept, the online solve, the newest pose and the
  /// calibration's estimates recorded.
  void finish_scan_step(std::size_t k, const Scan& scan) override;
  /// Solves the graph, warm-started; count_downweighted as PoseGraph::solve.
  void solve(bool count_downweighted);
  /// The compass on the newest node (its belief `newest`, updated in place) behind the filters'
  /// gate; adds the heading edge when it passes.
  bool update_compass(double yaw_world_rad, double sigma_rad, PoseGraphBelief& belief);
  /// Matches scan k against the candidates (candidate c at index in_belief[c] of the belief),
  /// adds the accepted matches as edges and updates the belief by each.
  void match(std::size_t k, const std::vector<std::pair<double, std::size_t>>& candidates,
             const std::vector<Eigen::Index>& in_belief, PoseGraphBelief& belief,
             SlamStepStats& stats);
  /// Writes the belief's means to the graph: the next solve's warm start, and where the old
  /// nodes of a windowed belief are held in the online solves (as the whole graph's candidates
  /// start its solves from their updated means).
  void write_means(const PoseGraphBelief& belief);
  /// What a match of the newest node against the belief's node c observes: its pose seen from c,
  /// through the range scale when estimated, with H and H P H^T.
  GaussianPose2 predict_match(const PoseGraphBelief& belief, Eigen::Index c,
                              Eigen::MatrixXd* H) const;
  /// The bias block of scan node `node` at time t_s: the prior at the first scan, the walk from
  /// the previous one after (the belief's bias variance grown by it).
  void add_bias_block(std::size_t node, double t_s, PoseGraphBelief& belief);

  ScanFrontEndConfig front_end_;
  PoseGraphSlamConfig config_;
  std::unique_ptr<PoseGraph> graph_;
  Eigen::Matrix3d start_cov_;  ///< node 0's covariance (zero when it is held fixed)
  PoseGraphCalibration calibration_;
  std::vector<GaussianPose2> motions_;  ///< motions_[i]: scan i from scan i-1 (or the start)
  std::unique_ptr<PoseGraphOnline> online_belief_;  ///< whole graph or windowed
  PoseGraphBelief step_belief_;                     ///< the newest node's belief during its step
  std::vector<GaussianPose2> online_;
  int downweighted_ = 0;
  std::vector<GaussianPose2> smoothed_;       ///< filled by finish(); cleared by the next scan
  double previous_t_s_ = 0.0;                 ///< the last scan's time (the bias's walk)
  std::pair<double, double> bias_{0.0, 0.0};  ///< the newest bias and its sd, rad
  /// Per GraphConstant: online, the constant and its sd; after finish(), the smoothed graph's.
  std::array<std::pair<double, double>, 5> constant_estimates_{};
  std::array<std::pair<double, double>, 5> smoothed_constants_{};
};

}  // namespace msislab
