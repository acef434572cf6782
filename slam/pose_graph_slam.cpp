#include "slam/pose_graph_slam.hpp"

#include <Eigen/Cholesky>
#include <algorithm>
#include <cmath>
#include <limits>

#include "slam/match_validation.hpp"
#include "slam/numerical_error.hpp"

namespace msislab {

PoseGraphSlam::PoseGraphSlam(const TrajectorySlamConfig& front_end,
                             const PoseGraphSlamConfig& config, const GaussianPose2& start_world)
    : front_end_(front_end),
      config_(config),
      graph_(std::make_unique<PoseGraph>(config.graph)),
      start_cov_(start_world.cov) {
  graph_->add_node(start_world.mean);
  // The start pose: a prior with its covariance, or held where it is when that is singular.
  if (Eigen::LLT<Eigen::Matrix3d>(start_world.cov).info() == Eigen::Success) {
    graph_->add_prior(0, start_world);
  } else {
    graph_->fix_node(0);
    start_cov_.setZero();
  }
  window_cov_ = start_cov_;
}

SlamStepStats PoseGraphSlam::add_scan(const Scan& scan) {
  smoothed_.clear();
  SlamStepStats stats;
  const bool motion_ok = scan.motion.mean.vector().allFinite() && scan.motion.cov.allFinite();
  const GaussianPose2 motion = motion_ok ? scan.motion : unknown_motion();
  const std::size_t k = motions_.size();
  const std::size_t node = k + 1;
  const bool windowed = config_.online_window_scans > 0;

  // The odometry edge (Eq. 2): the newest node's belief is the previous one's composed with the
  // motion, exact for its marginal since nothing else touches it yet; windowed, in the joint of
  // the kept old nodes and the window.
  PoseGraphBelief belief;
  if (windowed) {
    for (const std::size_t i : old_nodes_) {
      belief.nodes.push_back(i);
      belief.means.push_back(graph_->pose(i));
    }
    for (std::size_t i = window_first_; i < node; ++i) {
      belief.nodes.push_back(i);
      belief.means.push_back(graph_->pose(i));
    }
    belief.cov = window_cov_;
    belief.append_composed(node, static_cast<Eigen::Index>(belief.nodes.size()) - 1, motion);
  } else {
    const GaussianPose2 previous{graph_->pose(node - 1), k == 0 ? start_cov_ : online_.back().cov};
    const GaussianPose2 newest = compose(previous, motion);
    belief = {{node}, {newest.mean}, newest.cov, 0};
  }
  graph_->add_node(belief.means[static_cast<std::size_t>(belief.newest)]);
  graph_->add_relative(node - 1, node, motion, Eigen::Matrix3d::Identity(), false);
  motions_.push_back(motion);
  points_.push_back(finite_points(scan.points));
  ++totals_.scans;

  // The compass, before association as the filters do, behind the same gate.
  if (front_end_.compass_updates && std::isfinite(scan.compass_yaw_world_rad) &&
      scan.compass_sigma_rad > 0.0 &&
      update_compass(scan.compass_yaw_world_rad, scan.compass_sigma_rad, belief)) {
    graph_->add_heading(node, scan.compass_yaw_world_rad, scan.compass_sigma_rad);
    write_means(belief);
    stats.compass_accepted = true;
    ++totals_.compass_accepted;
  }

  if (!motion_ok || static_cast<int>(points_[k].size()) < front_end_.matching.min_inliers) {
    stats.skipped = true;
    ++totals_.skipped;
  } else {
    // Associate (paper Eq. 3-4): past scans whose estimated centre lies within gamma.
    const Pose2 newest_mean = belief.means[static_cast<std::size_t>(belief.newest)];
    std::vector<double> distances_m(k);
    for (std::size_t j = 0; j < k; ++j) {
      distances_m[j] = (graph_->pose(j + 1).translation() - newest_mean.translation()).norm();
    }
    const std::vector<std::pair<double, std::size_t>> candidates =
        nearest_candidates(distances_m, points_, front_end_);
    stats.candidates = static_cast<int>(candidates.size());
    if (!candidates.empty()) {
      std::vector<Eigen::Index> in_belief;
      if (windowed) {
        in_belief = append_outside_window(belief, candidates, k);
      } else {
        belief = whole_graph_belief(node, newest_mean, candidates);
        for (Eigen::Index c = 0; c < belief.newest; ++c) in_belief.push_back(c);
      }
      match(k, candidates, in_belief, belief, stats);
      write_means(belief);  // the updated means start the next solve
    }
    totals_.candidates += stats.candidates;
    totals_.matched += stats.matched;
    totals_.accepted += stats.accepted;
  }
  const Eigen::Index t = belief.newest;
  const GaussianPose2 newest{belief.means[static_cast<std::size_t>(t)], belief.node_cov(t)};
  require_finite(newest.mean.vector().allFinite() && newest.cov.allFinite(), "pose graph", k,
                 scan.t_s, "compass and match updates");
  if (windowed) keep_window(belief, k);
  if (config_.solve_every <= 1 || (k + 1) % static_cast<std::size_t>(config_.solve_every) == 0) {
    solve(!windowed);  // windowed, edges_downweighted waits for the smoothing solve
    require_finite(graph_->pose(node).vector().allFinite(), "pose graph", k, scan.t_s, "solve");
  }
  online_.push_back({graph_->pose(node), newest.cov});
  return stats;
}

bool PoseGraphSlam::update_compass(double yaw_world_rad, double sigma_rad,
                                   PoseGraphBelief& belief) {
  const Eigen::Index t = belief.newest;
  const auto residual = [&](Eigen::MatrixXd* H) -> Eigen::VectorXd {
    H->setZero(1, belief.cov.cols());
    (*H)(0, 3 * t + 2) = 1.0;
    return Eigen::VectorXd::Constant(
        1, normalize_angle(yaw_world_rad - belief.means[static_cast<std::size_t>(t)].yaw()));
  };
  // Linear in the yaw: one step is exact.
  const Eigen::MatrixXd R = Eigen::MatrixXd::Constant(1, 1, sigma_rad * sigma_rad);
  return belief.update(residual, R, 1, front_end_.compass_gate_chi2);
}

PoseGraphBelief PoseGraphSlam::whole_graph_belief(
    std::size_t node, const Pose2& newest_mean,
    const std::vector<std::pair<double, std::size_t>>& candidates) {
  PoseGraphBelief belief;
  for (const auto& candidate : candidates) {
    belief.nodes.push_back(candidate.second + 1);
    belief.means.push_back(graph_->pose(candidate.second + 1));
  }
  belief.nodes.push_back(node);
  belief.means.push_back(newest_mean);
  belief.newest = static_cast<Eigen::Index>(candidates.size());
  belief.cov = graph_->joint_covariance(belief.nodes);
  return belief;
}

void PoseGraphSlam::match(std::size_t k,
                          const std::vector<std::pair<double, std::size_t>>& candidates,
                          const std::vector<Eigen::Index>& in_belief, PoseGraphBelief& belief,
                          SlamStepStats& stats) {
  const std::size_t node = k + 1;
  // Predictions (Eq. 5): one after the other, each from the belief the earlier matches of this
  // scan left (the filters' default), or all from the belief before them (joint_update).
  std::vector<GaussianPose2> joint_predictions;
  Eigen::MatrixXd H;
  for (std::size_t c = 0; front_end_.joint_update && c < candidates.size(); ++c) {
    joint_predictions.push_back(belief.predict(in_belief[c], &H));
  }
  for (std::size_t c = 0; c < candidates.size(); ++c) {
    const std::size_t j = candidates[c].second;
    const GaussianPose2 predicted =
        front_end_.joint_update ? joint_predictions[c] : belief.predict(in_belief[c], &H);
    ValidatedMatch m = match_and_validate(points_[j], points_[k], predicted, front_end_.matching,
                                          front_end_.validation);
    stats.matched += m.match.valid;
    double nis = std::numeric_limits<double>::quiet_NaN();
    if (m.rejection == MatchRejection::kNone) {
      const Eigen::MatrixXd& A = m.observed;
      const Eigen::VectorXd r = A * pose_difference(m.match.estimate.mean, predicted.mean);
      const Eigen::MatrixXd S = A * (predicted.cov + m.match.estimate.cov) * A.transpose();
      nis = r.dot(S.ldlt().solve(r));
      const double gate = gate_for_dimensions(front_end_.innovation_gate_chi2, A.rows());
      if (nis > gate) {
        m.rejection = MatchRejection::kInnovation;
      } else {
        graph_->add_relative(j + 1, node, m.match.estimate, A, true);
        ++stats.accepted;
        // The update (Eq. 6-10).
        const auto residual = [&](Eigen::MatrixXd* H_match) -> Eigen::VectorXd {
          const Pose2 h = belief.predict(in_belief[c], &H).mean;
          *H_match = A * H;
          return A * pose_difference(m.match.estimate.mean, h);
        };
        belief.update(residual, A * m.match.estimate.cov * A.transpose(),
                      front_end_.iekf_iterations);
      }
    }
    stats.matches.push_back(record_of(j, k, m, predicted, nis));
    stats.matches.back().distance_m = candidates[c].first;
    stats.rejections.count(m);
    totals_.rejections.count(m);
  }
}

std::vector<Eigen::Index> PoseGraphSlam::append_outside_window(
    PoseGraphBelief& belief, const std::vector<std::pair<double, std::size_t>>& candidates,
    std::size_t k) {
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

void PoseGraphSlam::append_old(PoseGraphBelief& belief, std::size_t i) {
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
  if (chain <= static_cast<std::size_t>(config_.online_old_chain_scans)) {
    const std::size_t j = belief.nodes[static_cast<std::size_t>(from)];
    GaussianPose2 relative;  // node j to node i along the odometry: motions_[m] is node m to m + 1
    for (std::size_t m = std::min(i, j); m < std::max(i, j); ++m) {
      relative = compose(relative, motions_[m]);
    }
    if (j > i) relative = invert(relative);
    relative.mean = belief.means[static_cast<std::size_t>(from)].between(graph_->pose(i));
    belief.append_relative(i, from, relative);
    return;
  }
  // Its correlation with the belief is not known: the window's one approximation left.
  belief.append_independent(i, {graph_->pose(i), left_window_cov_.at(i)});
  ++old_uncorrelated_;
}

void PoseGraphSlam::write_means(const PoseGraphBelief& belief) {
  for (std::size_t i = 0; i < belief.nodes.size(); ++i) {
    graph_->set_pose(belief.nodes[i], belief.means[i]);
  }
}

void PoseGraphSlam::keep_window(const PoseGraphBelief& belief, std::size_t k) {
  const auto window_at = static_cast<Eigen::Index>(old_nodes_.size());
  const Eigen::Index kept = belief.newest - window_at + 1;  // the window's nodes, in order
  const Eigen::Index dropped = kept - std::min<Eigen::Index>(kept, config_.online_window_scans);
  left_window_cov_.resize(window_first_ + static_cast<std::size_t>(dropped),
                          Eigen::Matrix3d::Zero());
  for (Eigen::Index d = 0; d < dropped; ++d) {
    left_window_cov_[window_first_ + static_cast<std::size_t>(d)] = belief.node_cov(window_at + d);
  }
  std::vector<Eigen::Index> kept_at = keep_old_nodes(belief, k);
  for (Eigen::Index b = window_at + dropped; b <= belief.newest; ++b) kept_at.push_back(b);
  window_cov_ = belief.marginal(kept_at);
  window_first_ += static_cast<std::size_t>(dropped);
  graph_->hold_before(window_first_);
}

std::vector<Eigen::Index> PoseGraphSlam::keep_old_nodes(const PoseGraphBelief& belief,
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
      std::min(old.size(), static_cast<std::size_t>(std::max(0, config_.online_old_nodes)));
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

void PoseGraphSlam::solve(bool count_downweighted) const {
  downweighted_ = graph_->solve(count_downweighted).edges_downweighted;
}

void PoseGraphSlam::smooth() const {
  if (!smoothed_.empty() || motions_.empty()) return;
  graph_->hold_before(0);
  solve(true);
  std::vector<std::size_t> nodes;
  for (std::size_t i = 1; i <= motions_.size(); ++i) nodes.push_back(i);
  const std::vector<Eigen::Matrix3d> covariances = graph_->covariances(nodes);
  for (std::size_t i = 0; i < nodes.size(); ++i) {
    smoothed_.push_back({graph_->pose(nodes[i]), covariances[i]});
  }
}

GaussianPose2 PoseGraphSlam::scan_pose_world(std::size_t i) const {
  smooth();
  return require_finite(smoothed_.at(i), "pose graph", i);
}

}  // namespace msislab
