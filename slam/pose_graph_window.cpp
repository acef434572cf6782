// The pose-graph SLAM's online window (WindowedOnline, PoseGraphSlamConfig::online_window_scans >
// 0; slam/pose_graph_online.hpp and docs/pose_graph.md, "Long missions"): each scan's node
// composed onto the window, the candidates older than the window joining the belief, and the
// window kept from scan to scan.
#include <algorithm>
#include <limits>
#include <optional>

#include "slam/pose_graph_online.hpp"

namespace msislab {

WindowedOnline::WindowedOnline(PoseGraph& graph, const PoseGraphCalibration& calibration,
                               const std::vector<GaussianPose2>& motions,
                               const Eigen::MatrixXd& start_joint, int window_scans, int old_nodes,
                               int old_chain_scans)
    : graph_(graph),
      calibration_(calibration),
      motions_(motions),
      window_scans_(window_scans),
      old_nodes_max_(old_nodes),
      old_chain_scans_(old_chain_scans),
      window_cov_(start_joint) {}

PoseGraphBelief WindowedOnline::odometry_belief(std::size_t node, const GaussianPose2& motion) {
  // The odometry edge (Eq. 2) in the joint of the kept old nodes and the window: the newest node
  // composed onto the previous one.
  PoseGraphBelief belief;
  belief.parameters =
      calibration_.graph_parameters(node == 1 ? std::nullopt : std::optional(node - 1));
  for (const std::size_t i : old_nodes_) {
    belief.nodes.push_back(i);
    belief.means.push_back(graph_.pose(i));
  }
  for (std::size_t i = window_first_; i < node; ++i) {
    belief.nodes.push_back(i);
    belief.means.push_back(graph_.pose(i));
  }
  belief.cov = window_cov_;
  calibration_.append_odometry(belief, node, static_cast<Eigen::Index>(belief.nodes.size()) - 1,
                               motion);
  return belief;
}

std::vector<Eigen::Index> WindowedOnline::join_candidates(std::size_t k,
                                                          const PoseGraphCandidates& candidates,
                                                          PoseGraphBelief& belief) {
  const auto window_at = static_cast<Eigen::Index>(old_nodes_.size());
  std::vector<Eigen::Index> in_belief;
  for (const auto& candidate : candidates) {
    const std::size_t i = candidate.second + 1;
    if (i >= window_first_) {
      in_belief.push_back(window_at + static_cast<Eigen::Index>(i - window_first_));
      continue;
    }
    ++outside_window_matches_;
    auto at = std::find(belief.nodes.begin(), belief.nodes.end(), i);
    if (at == belief.nodes.end()) {
      append_old(belief, i);
      at = belief.nodes.end() - 1;
    }
    const auto index = static_cast<Eigen::Index>(at - belief.nodes.begin());
    if (index < window_at) old_used_[static_cast<std::size_t>(index)] = k;
    in_belief.push_back(index);
  }
  return in_belief;
}

void WindowedOnline::append_old(PoseGraphBelief& belief, std::size_t i) {
  // The nearest node of the belief along the odometry chain.
  Eigen::Index from = -1;
  std::size_t chain = std::numeric_limits<std::size_t>::max();
  for (std::size_t b = 0; b < belief.nodes.size(); ++b) {
    const std::size_t n = belief.nodes[b];
    const std::size_t d = n > i ? n - i : i - n;
    if (d < chain) {
      chain = d;
      from = static_cast<Eigen::Index>(b);
    }
  }
  if (chain <= static_cast<std::size_t>(old_chain_scans_) && calibration_.calibrates_odometry()) {
    append_old_through_calibration(belief, i, from);
    return;
  }
  if (chain <= static_cast<std::size_t>(old_chain_scans_)) {
    const std::size_t j = belief.nodes[static_cast<std::size_t>(from)];
    GaussianPose2 relative;  // node j to node i along the odometry: motions_[m] is node m to m + 1
    for (std::size_t m = std::min(i, j); m < std::max(i, j); ++m) {
      relative = compose(relative, motions_[m]);
    }
    if (j > i) relative = invert(relative);
    relative.mean = belief.means[static_cast<std::size_t>(from)].between(graph_.pose(i));
    belief.append_relative(i, from, relative);
    return;
  }
  // Its correlation with the belief is not known: the window's one approximation left.
  belief.append_independent(i, {graph_.pose(i), left_window_cov_.at(i)});
  ++old_uncorrelated_;
}

void WindowedOnline::append_old_through_calibration(PoseGraphBelief& belief, std::size_t i,
                                                    Eigen::Index from) const {
  // The odometry from node j to node i a motion at a time, each through the calibration (as
  // append_odometry; backward when i is older, the motions_[m] of node m to m + 1 inverted), at the
  // graph's headings; the nodes between marginalised, node i kept at the graph's mean.
  const std::size_t j = belief.nodes[static_cast<std::size_t>(from)];
  const auto first = static_cast<Eigen::Index>(belief.nodes.size());
  Eigen::Index at = from;
  for (std::size_t n = j; n != i;) {
    const std::size_t next = i < j ? n - 1 : n + 1;
    const std::size_t m = std::min(n, next);  // motions_[m] runs from node m to node m + 1
    const CalibratedMotion g = calibration_.calibrated_step(
        belief.parameters, motions_[m].mean, graph_.pose(m).yaw(), graph_.pose(m + 1).yaw(), m + 1);
    belief.append_through(next, at, motions_[m], g, calibration_.odometry_k_at(),
                          calibration_.odometry_ab_at(), i < j);
    at = static_cast<Eigen::Index>(belief.nodes.size()) - 1;
    n = next;
  }
  belief.drop(first, at - first);  // the nodes between
  belief.means.back() = graph_.pose(i);
}

void WindowedOnline::keep(const PoseGraphBelief& belief, std::size_t k) {
  const auto window_at = static_cast<Eigen::Index>(old_nodes_.size());
  const Eigen::Index kept = belief.newest - window_at + 1;  // the window's nodes, in order
  const Eigen::Index dropped = kept - std::min<Eigen::Index>(kept, window_scans_);
  left_window_cov_.resize(window_first_ + static_cast<std::size_t>(dropped),
                          Eigen::Matrix3d::Zero());
  for (Eigen::Index d = 0; d < dropped; ++d) {
    left_window_cov_[window_first_ + static_cast<std::size_t>(d)] = belief.node_cov(window_at + d);
  }
  std::vector<Eigen::Index> kept_at = keep_old_nodes(belief, k);
  for (Eigen::Index b = window_at + dropped; b <= belief.newest; ++b) kept_at.push_back(b);
  window_cov_ = belief.marginal(kept_at);
  window_first_ += static_cast<std::size_t>(dropped);
  graph_.hold_before(window_first_);
  // The constants too, once nodes are held: the belief estimates them online (with its nodes,
  // jointly); a solve over the held nodes' edges would inform them from nodes it takes as exact.
  graph_.hold_constants(window_first_ > 0);
}

std::vector<Eigen::Index> WindowedOnline::keep_old_nodes(const PoseGraphBelief& belief,
                                                         std::size_t k) {
  const auto window_at = static_cast<Eigen::Index>(old_nodes_.size());
  // The old nodes, most recently used first (this scan's first uses are used now).
  std::vector<std::pair<std::size_t, Eigen::Index>> old;  // (last used, index in the belief)
  for (Eigen::Index b = 0; b < window_at; ++b) {
    old.push_back({old_used_[static_cast<std::size_t>(b)], b});
  }
  const auto size = static_cast<Eigen::Index>(belief.nodes.size());
  for (Eigen::Index b = belief.newest + 1; b < size; ++b) old.push_back({k, b});
  std::stable_sort(old.begin(), old.end(),
                   [](const auto& a, const auto& b) { return a.first > b.first; });
  const std::size_t keep_old =
      std::min(old.size(), static_cast<std::size_t>(std::max(0, old_nodes_max_)));
  for (std::size_t o = keep_old; o < old.size(); ++o) {
    left_window_cov_.at(belief.nodes[static_cast<std::size_t>(old[o].second)]) =
        belief.node_cov(old[o].second);
  }
  old.resize(keep_old);
  std::sort(old.begin(), old.end(),
            [](const auto& a, const auto& b) { return a.second < b.second; });
  std::vector<Eigen::Index> kept_at;
  old_nodes_.clear();
  old_used_.clear();
  for (const auto& [used, b] : old) {
    kept_at.push_back(b);
    old_nodes_.push_back(belief.nodes[static_cast<std::size_t>(b)]);
    old_used_.push_back(used);
  }
  return kept_at;
}

}  // namespace msislab
