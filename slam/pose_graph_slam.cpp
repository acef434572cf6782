#include "slam/pose_graph_slam.hpp"

#include <Eigen/Cholesky>
#include <algorithm>
#include <cmath>
#include <limits>

#include "slam/iterated_ekf.hpp"
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
}

namespace {

/// The nodes a scan may touch (the newest last) as the graph knows them: their means and joint
/// covariance. Every edge the scan adds (odometry, compass, matches) involves only these nodes, so
/// an EKF update of this small joint gives exactly their marginal in the grown graph, to first
/// order: the filters' prediction and innovation, without solving the graph or computing its
/// covariance again for each match.
struct LocalBelief {
  std::vector<std::size_t> nodes;
  std::vector<Pose2> means;
  Eigen::MatrixXd cov;

  Eigen::Index newest() const { return static_cast<Eigen::Index>(nodes.size()) - 1; }

  /// The pose of the newest node seen from the belief's node c, with its Jacobian H (3 x 3n).
  GaussianPose2 predict(Eigen::Index c, Eigen::MatrixXd* H) const {
    const Eigen::Index t = newest();
    Eigen::Matrix3d J_c, J_t;
    const Pose2 h = means[c].between(means[t], &J_c, &J_t);
    H->setZero(3, cov.cols());
    H->block<3, 3>(0, 3 * c) = J_c;
    H->block<3, 3>(0, 3 * t) = J_t;
    const Eigen::Matrix3d P = *H * cov * H->transpose();
    return {h, 0.5 * (P + P.transpose())};
  }

  /// The filters' iterated EKF update (slam/iterated_ekf.hpp) of the whole belief behind their
  /// NIS gate (infinite: none); residual(H) gives z (-) h at the current means and sets H.
  /// False, and the belief unchanged, when the gate rejects the observation.
  template <class Residual>
  bool update(const Residual& residual, const Eigen::MatrixXd& R, int iterations,
              double gate_chi2 = std::numeric_limits<double>::infinity()) {
    Eigen::MatrixXd K, PHt;
    const auto gate = [&](const Eigen::VectorXd&, const Eigen::VectorXd&,
                          const Eigen::VectorXd& innovation, const Eigen::MatrixXd& S) {
      return innovation.dot(S.ldlt().solve(innovation)) <= gate_chi2;
    };
    if (!iterated_ekf_update(means.begin(), means.size(), cov, residual, R, iterations, gate, K,
                             PHt)) {
      return false;
    }
    cov.noalias() -= K * PHt.transpose();
    cov = 0.5 * (cov + cov.transpose());
    return true;
  }
};

}  // namespace

SlamStepStats PoseGraphSlam::add_scan(const Scan& scan) {
  smoothed_.clear();
  SlamStepStats stats;
  const bool motion_ok = scan.motion.mean.vector().allFinite() && scan.motion.cov.allFinite();
  const GaussianPose2 motion = motion_ok ? scan.motion : unknown_motion();
  const std::size_t k = motions_.size();
  const std::size_t node = k + 1;

  // The odometry edge (Eq. 2): the newest node's belief is the previous one's composed with the
  // motion, exact for its marginal since nothing else touches it yet.
  const GaussianPose2 previous{graph_->pose(node - 1), k == 0 ? start_cov_ : online_.back().cov};
  GaussianPose2 newest = compose(previous, motion);
  graph_->add_node(newest.mean);
  graph_->add_relative(node - 1, node, motion, Eigen::Matrix3d::Identity(), false);
  motions_.push_back(motion);
  points_.push_back(finite_points(scan.points));
  ++totals_.scans;

  // The compass, before association as the filters do, behind the same gate.
  if (front_end_.compass_updates && std::isfinite(scan.compass_yaw_world_rad) &&
      scan.compass_sigma_rad > 0.0 &&
      update_compass(node, scan.compass_yaw_world_rad, scan.compass_sigma_rad, newest)) {
    stats.compass_accepted = true;
    ++totals_.compass_accepted;
  }

  if (!motion_ok || static_cast<int>(points_[k].size()) < front_end_.matching.min_inliers) {
    stats.skipped = true;
    ++totals_.skipped;
  } else {
    // Associate (paper Eq. 3-4): past scans whose estimated centre lies within gamma.
    std::vector<double> distances_m(k);
    for (std::size_t j = 0; j < k; ++j) {
      distances_m[j] = (graph_->pose(j + 1).translation() - newest.mean.translation()).norm();
    }
    const std::vector<std::pair<double, std::size_t>> candidates =
        nearest_candidates(distances_m, points_, front_end_);
    stats.candidates = static_cast<int>(candidates.size());
    if (!candidates.empty()) newest = match(k, candidates, stats);
    totals_.candidates += stats.candidates;
    totals_.matched += stats.matched;
    totals_.accepted += stats.accepted;
  }
  require_finite(newest.mean.vector().allFinite() && newest.cov.allFinite(), "pose graph", k,
                 scan.t_s, "compass and match updates");
  if (config_.solve_every <= 1 || (k + 1) % static_cast<std::size_t>(config_.solve_every) == 0) {
    solve();
    require_finite(graph_->pose(node).vector().allFinite(), "pose graph", k, scan.t_s, "solve");
  }
  online_.push_back({graph_->pose(node), newest.cov});
  return stats;
}

bool PoseGraphSlam::update_compass(std::size_t node, double yaw_world_rad, double sigma_rad,
                                   GaussianPose2& newest) {
  LocalBelief belief{{node}, {newest.mean}, newest.cov};
  const auto residual = [&](Eigen::MatrixXd* H) -> Eigen::VectorXd {
    *H = Eigen::RowVector3d(0.0, 0.0, 1.0);
    return Eigen::VectorXd::Constant(1, normalize_angle(yaw_world_rad - belief.means[0].yaw()));
  };
  // Linear in the yaw: one step is exact.
  const Eigen::MatrixXd R = Eigen::MatrixXd::Constant(1, 1, sigma_rad * sigma_rad);
  if (!belief.update(residual, R, 1, front_end_.compass_gate_chi2)) return false;
  newest = {belief.means[0], belief.cov};
  graph_->add_heading(node, yaw_world_rad, sigma_rad);
  graph_->set_pose(node, newest.mean);
  return true;
}

GaussianPose2 PoseGraphSlam::match(std::size_t k,
                                   const std::vector<std::pair<double, std::size_t>>& candidates,
                                   SlamStepStats& stats) {
  const std::size_t node = k + 1;
  LocalBelief belief;
  for (const auto& candidate : candidates) belief.nodes.push_back(candidate.second + 1);
  belief.nodes.push_back(node);
  for (const std::size_t i : belief.nodes) belief.means.push_back(graph_->pose(i));
  belief.cov = graph_->joint_covariance(belief.nodes);

  // Predictions (Eq. 5): one after the other, each from the belief the earlier matches of this
  // scan left (the filters' default), or all from the belief before them (joint_update).
  std::vector<GaussianPose2> joint_predictions;
  Eigen::MatrixXd H;
  for (std::size_t c = 0; front_end_.joint_update && c < candidates.size(); ++c) {
    joint_predictions.push_back(belief.predict(static_cast<Eigen::Index>(c), &H));
  }
  for (std::size_t c = 0; c < candidates.size(); ++c) {
    const std::size_t j = candidates[c].second;
    const GaussianPose2 predicted = front_end_.joint_update
                                        ? joint_predictions[c]
                                        : belief.predict(static_cast<Eigen::Index>(c), &H);
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
          const Pose2 h = belief.predict(static_cast<Eigen::Index>(c), &H).mean;
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
  // The updated means start the next solve.
  for (std::size_t i = 0; i < belief.nodes.size(); ++i) {
    graph_->set_pose(belief.nodes[i], belief.means[i]);
  }
  const Eigen::Index t = belief.newest();
  return {belief.means.back(), belief.cov.block<3, 3>(3 * t, 3 * t)};
}

void PoseGraphSlam::solve() const { downweighted_ = graph_->solve().edges_downweighted; }

void PoseGraphSlam::smooth() const {
  if (!smoothed_.empty() || motions_.empty()) return;
  solve();
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
