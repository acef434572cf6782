#include "slam/pose_graph_slam.hpp"

#include <Eigen/Cholesky>
#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>
#include <utility>

#include "geometry/angles.hpp"
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
  // The calibration leads the belief from the start with its priors: the compass's bias (the
  // scans' nodes carry it in the graph, the first with the prior, the later ones through the
  // walk), then the range scale, the DVL's, the clock offset and the compass deviation's a and b
  // (one block each in the graph).
  const CalibrationStatesConfig& c = front_end.calibration;
  std::vector<double> prior_sd;
  if (c.heading_bias) prior_sd.push_back(c.heading_bias_sigma_deg * M_PI / 180.0);
  if (c.range_scale) {
    prior_sd.push_back(c.range_scale_sigma);
    graph_->add_constant(GraphConstant::kRangeScale, c.range_scale_prior, c.range_scale_prior,
                         c.range_scale_sigma);
  }
  if (c.dvl_scale) {
    prior_sd.push_back(c.dvl_scale_sigma);
    graph_->add_constant(GraphConstant::kDvlScale, c.dvl_scale_prior, c.dvl_scale_prior,
                         c.dvl_scale_sigma);
  }
  if (c.clock_offset) {
    prior_sd.push_back(c.clock_offset_sigma_s);
    graph_->add_constant(GraphConstant::kClockOffset, c.clock_offset_prior_s,
                         c.clock_offset_prior_s, c.clock_offset_sigma_s);
  }
  if (c.compass_deviation) {
    const double sigma_rad = c.compass_deviation_sigma_deg * kDegToRad;
    for (const auto& [which, prior_deg] :
         {std::pair(GraphConstant::kDeviationCos, c.compass_deviation_cos_prior_deg),
          std::pair(GraphConstant::kDeviationSin, c.compass_deviation_sin_prior_deg)}) {
      prior_sd.push_back(sigma_rad);
      graph_->add_constant(which, prior_deg * kDegToRad, prior_deg * kDegToRad, sigma_rad);
    }
  }
  const auto p = static_cast<Eigen::Index>(prior_sd.size());
  window_cov_ = Eigen::MatrixXd::Zero(p + 3, p + 3);
  for (Eigen::Index i = 0; i < p; ++i) window_cov_(i, i) = std::pow(prior_sd[i], 2);
  window_cov_.bottomRightCorner<3, 3>() = start_cov_;
  newest_joint_ = window_cov_;
}

SlamStepStats PoseGraphSlam::add_scan(const Scan& scan) {
  smoothed_.clear();
  SlamStepStats stats;
  const bool motion_ok = scan.motion.mean.vector().allFinite() && scan.motion.cov.allFinite();
  const GaussianPose2 motion = motion_ok ? scan.motion : unknown_motion();
  const std::size_t k = motions_.size();
  const std::size_t node = k + 1;

  PoseGraphBelief belief = odometry_belief(node, motion);
  graph_->add_node(belief.means[static_cast<std::size_t>(belief.newest)]);
  graph_->add_odometry(node - 1, node, motion, start_deviated(node));
  if (estimates_heading_bias()) add_bias_block(node, scan.t_s, belief);
  motions_.push_back(motion);
  velocities_.push_back(scan.velocity_vehicle.allFinite() ? scan.velocity_vehicle
                                                          : Eigen::Vector3d::Zero());
  points_.push_back(finite_points(scan.points));
  ++totals_.scans;

  // The compass, before association as the filters do, behind the same gate.
  if (front_end_.compass_updates && std::isfinite(scan.compass_yaw_world_rad) &&
      scan.compass_sigma_rad > 0.0 &&
      update_compass(scan.compass_yaw_world_rad, scan.compass_sigma_rad, belief)) {
    if (estimates_heading_bias()) {
      graph_->add_biased_heading(node, bias_node(node), scan.compass_yaw_world_rad,
                                 scan.compass_sigma_rad);
    } else {
      graph_->add_heading(node, scan.compass_yaw_world_rad, scan.compass_sigma_rad);
    }
    write_means(belief);
    stats.compass_accepted = true;
    ++totals_.compass_accepted;
  }

  if (!motion_ok || static_cast<int>(points_[k].size()) < front_end_.matching.min_inliers) {
    stats.skipped = true;
    ++totals_.skipped;
  } else {
    associate_and_match(k, belief, stats);
  }
  finish_scan(k, scan.t_s, belief);
  return stats;
}

PoseGraphBelief PoseGraphSlam::odometry_belief(std::size_t node, const GaussianPose2& motion) {
  // The odometry edge (Eq. 2): the newest node's belief is the previous one's composed with the
  // motion, exact for its marginal since nothing else touches it yet; windowed, in the joint of
  // the kept old nodes and the window.
  const std::size_t k = node - 1;
  PoseGraphBelief belief;
  belief.parameters = graph_parameters(k == 0 ? std::nullopt : std::optional(node - 1));
  if (config_.online_window_scans > 0) {
    for (const std::size_t i : old_nodes_) {
      belief.nodes.push_back(i);
      belief.means.push_back(graph_->pose(i));
    }
    for (std::size_t i = window_first_; i < node; ++i) {
      belief.nodes.push_back(i);
      belief.means.push_back(graph_->pose(i));
    }
    belief.cov = window_cov_;
    append_odometry(belief, node, static_cast<Eigen::Index>(belief.nodes.size()) - 1, motion);
  } else if (belief.parameters.size() > 0) {
    // The calibration's joint with the newest node, carried from scan to scan; the previous node
    // marginalised once the new one is composed onto it.
    PoseGraphBelief chain{
        {node - 1}, {graph_->pose(node - 1)}, newest_joint_, 0, belief.parameters};
    append_odometry(chain, node, 0, motion);
    belief = {{node}, {chain.means[1]}, chain.marginal({1}), 0, chain.parameters};
  } else {
    const GaussianPose2 previous{graph_->pose(node - 1), k == 0 ? start_cov_ : online_.back().cov};
    const GaussianPose2 newest = compose(previous, motion);
    belief = {{node}, {newest.mean}, newest.cov, 0, {}};
  }
  return belief;
}

void PoseGraphSlam::associate_and_match(std::size_t k, PoseGraphBelief& belief,
                                        SlamStepStats& stats) {
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
    if (config_.online_window_scans > 0) {
      in_belief = append_outside_window(belief, candidates, k);
    } else {
      belief = whole_graph_belief(k + 1, newest_mean, candidates);
      for (Eigen::Index c = 0; c < belief.newest; ++c) in_belief.push_back(c);
    }
    match(k, candidates, in_belief, belief, stats);
    write_means(belief);  // the updated means start the next solve
  }
  totals_.candidates += stats.candidates;
  totals_.matched += stats.matched;
  totals_.accepted += stats.accepted;
}

void PoseGraphSlam::finish_scan(std::size_t k, double t_s, const PoseGraphBelief& belief) {
  const std::size_t node = k + 1;
  const bool windowed = config_.online_window_scans > 0;
  const Eigen::Index t = belief.newest;
  const GaussianPose2 newest{belief.means[static_cast<std::size_t>(t)], belief.node_cov(t)};
  require_finite(newest.mean.vector().allFinite() && newest.cov.allFinite(), "pose graph", k, t_s,
                 "compass and match updates");
  if (windowed) {
    keep_window(belief, k);
  } else if (belief.parameters.size() > 0) {
    newest_joint_ = belief.marginal({t});
  }
  if (config_.solve_every <= 1 || (k + 1) % static_cast<std::size_t>(config_.solve_every) == 0) {
    solve(!windowed);  // windowed, edges_downweighted waits for the smoothing solve
    require_finite(graph_->pose(node).vector().allFinite(), "pose graph", k, t_s, "solve");
  }
  online_.push_back({graph_->pose(node), newest.cov});
  if (estimates_heading_bias()) {
    bias_ = {graph_->heading_bias(bias_node(node)), std::sqrt(belief.cov(0, 0))};
  }
  for (const GraphConstant which : estimated_constants()) {
    const Eigen::Index r = constant_at(which);
    constant_estimates_[static_cast<std::size_t>(which)] = {graph_->constant(which),
                                                            std::sqrt(belief.cov(r, r))};
  }
}

bool PoseGraphSlam::update_compass(double yaw_world_rad, double sigma_rad,
                                   PoseGraphBelief& belief) {
  const Eigen::Index t = belief.newest;
  const auto residual = [&](Eigen::MatrixXd* H) -> Eigen::VectorXd {
    H->setZero(1, belief.cov.cols());
    const double psi = belief.means[static_cast<std::size_t>(t)].yaw();
    (*H)(0, belief.at(t) + 2) = 1.0;
    // Through the bias when the belief carries it (its first parameter): h = yaw + b.
    const double bias_rad = estimates_heading_bias() ? belief.parameters(0) : 0.0;
    if (estimates_heading_bias()) (*H)(0, 0) = 1.0;
    double deviation_rad = 0.0;
    if (front_end_.calibration.compass_deviation) {
      // And its deviation: h + a cos(psi) + b sin(psi), dh/dpsi = 1 + d'(psi).
      const Eigen::Index ab_at = constant_at(GraphConstant::kDeviationCos);
      const Eigen::Vector2d ab = belief.parameters.segment<2>(ab_at);
      const Eigen::Vector2d basis(std::cos(psi), std::sin(psi));
      deviation_rad = ab.dot(basis);
      H->block<1, 2>(0, ab_at) = basis.transpose();
      (*H)(0, belief.at(t) + 2) += ab.dot(Eigen::Vector2d(-std::sin(psi), std::cos(psi)));
    }
    return Eigen::VectorXd::Constant(
        1, normalize_angle(yaw_world_rad - psi - bias_rad - deviation_rad));
  };
  // Linear in the yaw (nearly, with the deviation): one step.
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
  belief.parameters = graph_parameters(node);
  std::vector<std::size_t> bias_nodes;
  if (estimates_heading_bias()) bias_nodes.push_back(bias_node(node));
  belief.cov = graph_->joint_covariance(belief.nodes, bias_nodes, estimated_constants());
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
    joint_predictions.push_back(predict_match(belief, in_belief[c], &H));
  }
  for (std::size_t c = 0; c < candidates.size(); ++c) {
    const std::size_t j = candidates[c].second;
    const GaussianPose2 predicted =
        front_end_.joint_update ? joint_predictions[c] : predict_match(belief, in_belief[c], &H);
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
        if (estimates_range_scale() || front_end_.calibration.clock_offset) {
          graph_->add_match(j + 1, node, m.match.estimate, A, velocities_.at(j), velocities_.at(k));
        } else {
          graph_->add_relative(j + 1, node, m.match.estimate, A, true);
        }
        ++stats.accepted;
        // The update (Eq. 6-10).
        const auto residual = [&](Eigen::MatrixXd* H_match) -> Eigen::VectorXd {
          const Pose2 h = predict_match(belief, in_belief[c], &H).mean;
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

void PoseGraphSlam::write_means(const PoseGraphBelief& belief) {
  for (std::size_t i = 0; i < belief.nodes.size(); ++i) {
    graph_->set_pose(belief.nodes[i], belief.means[i]);
  }
  if (estimates_heading_bias()) {
    graph_->set_heading_bias(bias_node(belief.nodes[static_cast<std::size_t>(belief.newest)]),
                             belief.parameters(0));
  }
  for (const GraphConstant which : estimated_constants()) {
    graph_->set_constant(which, belief.parameters(constant_at(which)));
  }
}

void PoseGraphSlam::solve(bool count_downweighted) const {
  downweighted_ = graph_->solve(count_downweighted).edges_downweighted;
}

void PoseGraphSlam::smooth() const {
  if (!smoothed_.empty() || motions_.empty()) return;
  graph_->hold_before(0);
  graph_->hold_constants(false);
  solve(true);
  std::vector<std::size_t> nodes;
  for (std::size_t i = 1; i <= motions_.size(); ++i) nodes.push_back(i);
  const std::vector<Eigen::Matrix3d> covariances = graph_->covariances(nodes);
  for (std::size_t i = 0; i < nodes.size(); ++i) {
    smoothed_.push_back({graph_->pose(nodes[i]), covariances[i]});
  }
  // The scales as the whole graph knows them: the smoothed values, the information's sd.
  const std::vector<GraphConstant> scales = estimated_constants();
  if (!scales.empty()) {
    const Eigen::MatrixXd C = graph_->joint_covariance({}, {}, scales);
    for (std::size_t i = 0; i < scales.size(); ++i) {
      const auto r = static_cast<Eigen::Index>(i);
      smoothed_constants_[static_cast<std::size_t>(scales[i])] = {graph_->constant(scales[i]),
                                                                  std::sqrt(C(r, r))};
    }
  }
}

GaussianPose2 PoseGraphSlam::scan_pose_world(std::size_t i) const {
  smooth();
  return require_finite(smoothed_.at(i), "pose graph", i);
}

}  // namespace msislab
