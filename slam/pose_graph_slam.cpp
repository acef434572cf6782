#include "slam/pose_graph_slam.hpp"

#include <Eigen/Cholesky>
#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>
#include <stdexcept>
#include <utility>

#include "geometry/angles.hpp"
#include "slam/match_validation.hpp"
#include "slam/numerical_error.hpp"

namespace msislab {
namespace {

/// The start pose can be a prior: its covariance is positive definite.
bool start_has_prior(const Eigen::Matrix3d& cov) {
  return Eigen::LLT<Eigen::Matrix3d>(cov).info() == Eigen::Success;
}

}  // namespace

PoseGraphSlam::PoseGraphSlam(const ScanFrontEndConfig& front_end,
                             const CalibrationStatesConfig& calibration,
                             const PoseGraphSlamConfig& config, const GaussianPose2& start_world)
    : front_end_(front_end),
      config_(config),
      graph_(std::make_unique<PoseGraph>(config.graph)),
      start_cov_(start_has_prior(start_world.cov) ? start_world.cov : Eigen::Matrix3d::Zero()),
      calibration_(calibration, *graph_, start_cov_) {
  graph_->add_node(start_world.mean);
  // The start pose: a prior with its covariance, or held where it is when that is singular.
  if (start_has_prior(start_world.cov)) {
    graph_->add_prior(0, start_world);
  } else {
    graph_->fix_node(0);
  }
  // The calibration leads the belief from the start with its priors: the compass's bias (the
  // scans' nodes carry it in the graph, the first with the prior, the later ones through the
  // walk), then the range scale, the DVL's, the clock offset and the compass deviation's a and b
  // (one block each in the graph).
  const CalibrationStatesConfig& c = calibration;
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
  Eigen::MatrixXd start_joint = Eigen::MatrixXd::Zero(p + 3, p + 3);
  for (Eigen::Index i = 0; i < p; ++i) start_joint(i, i) = std::pow(prior_sd[i], 2);
  start_joint.bottomRightCorner<3, 3>() = start_cov_;
  if (config.online_window_scans > 0) {
    online_belief_ = std::make_unique<WindowedOnline>(
        *graph_, calibration_, motions_, start_joint, config.online_window_scans,
        config.online_old_nodes, config.online_old_chain_scans);
  } else {
    online_belief_ = std::make_unique<WholeGraphOnline>(*graph_, calibration_, start_joint);
  }
}

void PoseGraphSlam::predict_scan(const Scan& scan, const GaussianPose2& motion) {
  smoothed_.clear();
  const std::size_t node = motions_.size() + 1;
  step_belief_ = online_belief_->odometry_belief(node, motion);
  graph_->add_node(step_belief_.means[static_cast<std::size_t>(step_belief_.newest)]);
  graph_->add_odometry(node - 1, node, motion, calibration_.start_deviated(node));
  if (calibration_.estimates_heading_bias()) add_bias_block(node, scan.t_s, step_belief_);
  motions_.push_back(motion);
}

bool PoseGraphSlam::update_compass_reading(const Scan& scan, SlamStepStats& /*stats*/) {
  // Before association, as the filters do, behind the same gate.
  if (!update_compass(scan.compass_yaw_world_rad, scan.compass_sigma_rad, step_belief_)) {
    return false;
  }
  const std::size_t node = motions_.size();
  if (calibration_.estimates_heading_bias()) {
    graph_->add_biased_heading(node, calibration_.bias_node(node), scan.compass_yaw_world_rad,
                               scan.compass_sigma_rad);
  } else {
    graph_->add_heading(node, scan.compass_yaw_world_rad, scan.compass_sigma_rad);
  }
  write_means(step_belief_);
  return true;
}

std::vector<double> PoseGraphSlam::newest_scan_distances_m() const {
  // Association (paper Eq. 3-4) by the estimated centres: the graph's, the belief's newest.
  const Pose2& newest_mean = step_belief_.means[static_cast<std::size_t>(step_belief_.newest)];
  const std::size_t k = motions_.size() - 1;
  std::vector<double> distances_m(k);
  for (std::size_t j = 0; j < k; ++j) {
    distances_m[j] = (graph_->pose(j + 1).translation() - newest_mean.translation()).norm();
  }
  return distances_m;
}

void PoseGraphSlam::update_with_matches(std::size_t k, const ScanCandidates& candidates,
                                        const Scan& /*scan*/, SlamStepStats& stats) {
  if (candidates.empty()) return;
  PoseGraphBelief& belief = step_belief_;
  const std::vector<Eigen::Index> in_belief =
      online_belief_->join_candidates(k, candidates, belief);
  match(k, candidates, in_belief, belief, stats);
  write_means(belief);  // the updated means start the next solve
}

void PoseGraphSlam::finish_scan_step(std::size_t k, const Scan& scan) {
  const double t_s = scan.t_s;
  const PoseGraphBelief& belief = step_belief_;
  const std::size_t node = k + 1;
  const Eigen::Index t = belief.newest;
  const GaussianPose2 newest{belief.means[static_cast<std::size_t>(t)], belief.node_cov(t)};
  require_finite(newest.mean.vector().allFinite() && newest.cov.allFinite(), "pose graph", k, t_s,
                 "compass and match updates");
  online_belief_->keep(belief, k);
  if (config_.solve_every <= 1 || (k + 1) % static_cast<std::size_t>(config_.solve_every) == 0) {
    solve(online_belief_->counts_downweighted_online());
    require_finite(graph_->pose(node).vector().allFinite(), "pose graph", k, t_s, "solve");
  }
  online_.push_back({graph_->pose(node), newest.cov});
  if (calibration_.estimates_heading_bias()) {
    bias_ = {graph_->heading_bias(calibration_.bias_node(node)), std::sqrt(belief.cov(0, 0))};
  }
  for (const GraphConstant which : calibration_.estimated_constants()) {
    const Eigen::Index r = calibration_.constant_at(which);
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
    const bool biased = calibration_.estimates_heading_bias();
    const double bias_rad = biased ? belief.parameters(0) : 0.0;
    if (biased) (*H)(0, 0) = 1.0;
    double deviation_rad = 0.0;
    if (calibration_.config().compass_deviation) {
      // And its deviation: h + a cos(psi) + b sin(psi), dh/dpsi = 1 + d'(psi).
      const Eigen::Index ab_at = calibration_.constant_at(GraphConstant::kDeviationCos);
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
        if (calibration_.estimates_range_scale() || calibration_.config().clock_offset) {
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
  if (calibration_.estimates_heading_bias()) {
    graph_->set_heading_bias(
        calibration_.bias_node(belief.nodes[static_cast<std::size_t>(belief.newest)]),
        belief.parameters(0));
  }
  for (const GraphConstant which : calibration_.estimated_constants()) {
    graph_->set_constant(which, belief.parameters(calibration_.constant_at(which)));
  }
}

void PoseGraphSlam::solve(bool count_downweighted) {
  downweighted_ = graph_->solve(count_downweighted).edges_downweighted;
}

void PoseGraphSlam::finish() {
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
  const std::vector<GraphConstant> scales = calibration_.estimated_constants();
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
  if (smoothed_.size() != motions_.size()) {
    throw std::logic_error(
        "pose graph: scan_pose_world before finish() (call it after the last scan)");
  }
  return require_finite(smoothed_.at(i), "pose graph", i);
}

}  // namespace msislab
