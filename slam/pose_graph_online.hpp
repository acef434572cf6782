// How the pose-graph SLAM keeps what it knows of a scan's nodes from one scan to the next (the
// belief each step starts from and updates; slam/pose_graph_slam.hpp, docs/pose_graph.md): two
// strategies, chosen by PoseGraphSlamConfig::online_window_scans.
//   - WholeGraphOnline (0): the candidates' joint with the newest node from the whole graph's
//     information, factored every scan; the calibration's joint with the newest node carried from
//     scan to scan. The online solves free every node.
//   - WindowedOnline (W > 0), for long missions: the joint covariance of the newest W nodes kept
//     by the EKF instead, each scan's node composed onto it and the nodes that fall out of the
//     window dropped (marginalised). A candidate older than the window joins as the nearest node
//     of the belief composed with the odometry between them when that is at most
//     online_old_chain_scans away, else with its last marginal, uncorrelated with the window (the
//     one approximation left, counted); the online_old_nodes most recently matched old nodes
//     stay in the joint. The online solves hold the nodes older than the window.
#pragma once

#include <Eigen/Core>
#include <cstddef>
#include <utility>
#include <vector>

#include "geometry/gaussian_pose.hpp"
#include "slam/pose_graph.hpp"
#include "slam/pose_graph_belief.hpp"
#include "slam/pose_graph_calibration.hpp"

namespace msislab {

/// The candidates of a scan, (distance, scan index), nearest first (slam/scan_front_end.hpp).
using PoseGraphCandidates = std::vector<std::pair<double, std::size_t>>;

class PoseGraphOnline {
 public:
  virtual ~PoseGraphOnline() = default;
  /// The newest node's belief after the odometry edge to it (Eq. 2), `node` the new node (scan
  /// node - 1) and `motion` from the previous one.
  virtual PoseGraphBelief odometry_belief(std::size_t node, const GaussianPose2& motion) = 0;
  /// The belief the matches of scan k update: the candidates joined to the newest node's belief
  /// (which may be rebuilt), and each candidate's index in it, in the candidates' order.
  virtual std::vector<Eigen::Index> join_candidates(std::size_t k,
                                                    const PoseGraphCandidates& candidates,
                                                    PoseGraphBelief& belief) = 0;
  /// The end of scan k's step: what the next scan starts from kept, nodes held in the graph's
  /// online solves as the strategy needs.
  virtual void keep(const PoseGraphBelief& belief, std::size_t k) = 0;
  /// Whether an online solve counts the edges the robust loss sets aside (windowed, that waits for
  /// the smoothing solve).
  virtual bool counts_downweighted_online() const = 0;
  /// The candidates so far that were older than the window (0 for the whole graph).
  virtual int matches_outside_window() const { return 0; }
  /// The old nodes that joined the belief uncorrelated with it (0 for the whole graph).
  virtual int old_nodes_uncorrelated() const { return 0; }
};

class WholeGraphOnline final : public PoseGraphOnline {
 public:
  /// start_joint: the calibration's priors and node 0's covariance (parameters first).
  WholeGraphOnline(PoseGraph& graph, const PoseGraphCalibration& calibration,
                   const Eigen::MatrixXd& start_joint);
  PoseGraphBelief odometry_belief(std::size_t node, const GaussianPose2& motion) override;
  /// The scan's nodes as the whole graph knows them: the candidates' (in their order), then the
  /// newest's (the belief's mean, with the covariance from the graph's information).
  std::vector<Eigen::Index> join_candidates(std::size_t k, const PoseGraphCandidates& candidates,
                                            PoseGraphBelief& belief) override;
  void keep(const PoseGraphBelief& belief, std::size_t k) override;
  bool counts_downweighted_online() const override { return true; }

 private:
  PoseGraph& graph_;  ///< factored for the candidates' joint (joint_covariance)
  const PoseGraphCalibration& calibration_;
  /// With the calibration: its joint with the newest node; without: the newest node's
  /// covariance (node 0's before the first scan).
  Eigen::MatrixXd newest_joint_;
};

class WindowedOnline final : public PoseGraphOnline {
 public:
  /// motions: motions[i] is scan i from scan i - 1 (the caller's, growing; it must outlive this).
  WindowedOnline(PoseGraph& graph, const PoseGraphCalibration& calibration,
                 const std::vector<GaussianPose2>& motions, const Eigen::MatrixXd& start_joint,
                 int window_scans, int old_nodes, int old_chain_scans);
  PoseGraphBelief odometry_belief(std::size_t node, const GaussianPose2& motion) override;
  /// The candidates' indices in the belief (the kept old nodes, the window, the newest node), an
  /// old candidate not in it appended (append_old); k, the scan, marks the old ones used.
  std::vector<Eigen::Index> join_candidates(std::size_t k, const PoseGraphCandidates& candidates,
                                            PoseGraphBelief& belief) override;
  /// Keeps the window's part of the belief and the online_old_nodes most recently used old nodes,
  /// dropping (marginalising) the others with their marginal stored, and holds the nodes older
  /// than the window in the graph's online solves.
  void keep(const PoseGraphBelief& belief, std::size_t k) override;
  bool counts_downweighted_online() const override { return false; }
  int matches_outside_window() const override { return outside_window_matches_; }
  int old_nodes_uncorrelated() const override { return old_uncorrelated_; }

 private:
  /// Appends old node i to the belief, composed from the nearest node of the belief along the
  /// odometry (online_old_chain_scans), or with its last marginal, uncorrelated.
  void append_old(PoseGraphBelief& belief, std::size_t i);
  /// With the odometry through the calibration: appends old node i composed from the belief's
  /// node at `from` along the odometry, correlated with the calibration.
  void append_old_through_calibration(PoseGraphBelief& belief, std::size_t i,
                                      Eigen::Index from) const;
  /// The belief's indices of the old nodes kept (in the belief's order) and old_nodes_,
  /// old_used_ set to them; those dropped leave their marginal in left_window_cov_.
  std::vector<Eigen::Index> keep_old_nodes(const PoseGraphBelief& belief, std::size_t k);

  PoseGraph& graph_;
  const PoseGraphCalibration& calibration_;
  const std::vector<GaussianPose2>& motions_;
  int window_scans_, old_nodes_max_, old_chain_scans_;
  /// The joint covariance of the kept old nodes and nodes window_first_.. (the newest last), and
  /// each old node's marginal from when it left the window or the kept old nodes.
  std::size_t window_first_ = 0;
  Eigen::MatrixXd window_cov_;
  std::vector<Eigen::Matrix3d> left_window_cov_;
  /// The old nodes kept (first in window_cov_'s order), and the scan that last matched each (the
  /// scan's index k).
  std::vector<std::size_t> old_nodes_, old_used_;
  int old_uncorrelated_ = 0;
  int outside_window_matches_ = 0;
};

}  // namespace msislab
