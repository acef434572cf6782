#include "slam/pose_graph_slam.hpp"

#include <Eigen/Cholesky>
#include <cmath>
#include <limits>

#include "slam/match_validation.hpp"

namespace msislab {

PoseGraphSlam::PoseGraphSlam(const TrajectorySlamConfig& front_end,
                             const PoseGraphSlamConfig& config, const GaussianPose2& start_world)
    : front_end_(front_end), config_(config), graph_(std::make_unique<PoseGraph>(config.graph)) {
  graph_->add_node(start_world.mean);
  // The start pose: a prior with its covariance, or held where it is when that is singular.
  if (Eigen::LLT<Eigen::Matrix3d>(start_world.cov).info() == Eigen::Success) {
    graph_->add_prior(0, start_world);
  } else {
    graph_->fix_node(0);
  }
}

SlamStepStats PoseGraphSlam::add_scan(const Scan& scan) {
  smoothed_.clear();
  SlamStepStats stats;
  const bool motion_ok = scan.motion.mean.vector().allFinite() && scan.motion.cov.allFinite();
  const GaussianPose2 motion = motion_ok ? scan.motion : unknown_motion();
  const std::size_t k = motions_.size();
  const std::size_t node = k + 1;
  graph_->add_node(graph_->pose(node - 1).compose(motion.mean));
  graph_->add_relative(node - 1, node, motion, Eigen::Matrix3d::Identity(), false);
  motions_.push_back(motion);
  points_.push_back(finite_points(scan.points));
  ++totals_.scans;
  if (front_end_.compass_updates && std::isfinite(scan.compass_yaw_world_rad) &&
      scan.compass_sigma_rad > 0.0) {
    graph_->add_heading(node, scan.compass_yaw_world_rad, scan.compass_sigma_rad);
    stats.compass_accepted = true;
    ++totals_.compass_accepted;
  }

  if (!motion_ok || static_cast<int>(points_[k].size()) < front_end_.matching.min_inliers) {
    stats.skipped = true;
    ++totals_.skipped;
  } else {
    // Associate (paper Eq. 3-4): past scans whose estimated centre lies within gamma.
    const Pose2 newest = graph_->pose(node);
    std::vector<double> distances_m(k);
    for (std::size_t j = 0; j < k; ++j) {
      distances_m[j] = (graph_->pose(j + 1).translation() - newest.translation()).norm();
    }
    const std::vector<std::pair<double, std::size_t>> candidates =
        nearest_candidates(distances_m, points_, front_end_);
    stats.candidates = static_cast<int>(candidates.size());
    for (const auto& [distance_m, j] : candidates) {
      // The prediction: the graph's relative pose, with the odometry chain's covariance.
      GaussianPose2 chain{Pose2(), Eigen::Matrix3d::Zero()};
      for (std::size_t i = j + 1; i <= k; ++i) chain = compose(chain, motions_[i]);
      const GaussianPose2 predicted{graph_->pose(j + 1).between(newest), chain.cov};
      ValidatedMatch m = match_and_validate(points_[j], points_[k], predicted, front_end_.matching,
                                            front_end_.validation);
      stats.matched += m.match.valid;
      double nis = std::numeric_limits<double>::quiet_NaN();
      if (m.rejection == MatchRejection::kNone) {
        const Eigen::MatrixXd& A = m.observed;
        const Eigen::VectorXd r = A * pose_difference(m.match.estimate.mean, predicted.mean);
        const Eigen::MatrixXd S = A * (predicted.cov + m.match.estimate.cov) * A.transpose();
        nis = r.dot(S.ldlt().solve(r));
        const double gate =
            A.rows() == 3 ? front_end_.innovation_gate_chi2
                          : chi2_quantile(1.0 - chi2_survival(front_end_.innovation_gate_chi2, 3),
                                          static_cast<int>(A.rows()));
        if (nis > gate) {
          m.rejection = MatchRejection::kInnovation;
        } else {
          graph_->add_relative(j + 1, node, m.match.estimate, A, true);
          ++stats.accepted;
        }
      }
      stats.matches.push_back(record_of(j, k, m, predicted, nis));
      stats.matches.back().distance_m = distance_m;
      stats.rejections.count(m);
      totals_.rejections.count(m);
    }
    totals_.candidates += stats.candidates;
    totals_.matched += stats.matched;
    totals_.accepted += stats.accepted;
  }
  if (config_.solve_every <= 1 || (k + 1) % static_cast<std::size_t>(config_.solve_every) == 0) {
    solve();
  }
  online_.push_back({graph_->pose(node), graph_->covariances({node}).front()});
  return stats;
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
  return smoothed_.at(i);
}

}  // namespace msislab
