#include "slam/pose_graph.hpp"

#include <ceres/ceres.h>

#include <Eigen/Cholesky>
#include <Eigen/SparseCholesky>
#include <Eigen/SparseCore>
#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

#include "slam/pose_graph_edges.hpp"

namespace msislab {

namespace {

using pose_graph_edges::BiasedHeadingCost;
using pose_graph_edges::BiasPriorCost;
using pose_graph_edges::BiasWalkCost;
using pose_graph_edges::CauchyLoss;
using pose_graph_edges::DynamicCovarianceScalingLoss;
using pose_graph_edges::HeadingCost;
using pose_graph_edges::PriorCost;
using pose_graph_edges::RelativeCost;

/// W with W S W^T = I for a positive definite S: the inverse of its lower Cholesky factor.
Eigen::MatrixXd whitening(const Eigen::MatrixXd& S) {
  const Eigen::LLT<Eigen::MatrixXd> llt(S);
  if (llt.info() != Eigen::Success) {
    throw std::invalid_argument("pose graph: an edge covariance is not positive definite");
  }
  return llt.matrixL().solve(Eigen::MatrixXd::Identity(S.rows(), S.cols()));
}

}  // namespace

struct PoseGraph::Problem {
  ceres::Problem problem;
  /// The robust edges, to count the down-weighted ones after a solve.
  std::vector<ceres::ResidualBlockId> robust;
  /// c^2 of the robust losses now: the configured one, or more during a graduated start.
  double c2 = 0.0;
};

PoseGraph::PoseGraph(const PoseGraphConfig& config)
    : config_(config), problem_(std::make_unique<Problem>()) {
  problem_->c2 = config_.robust_scale_chi2;
  poses_.reserve(kMaxNodes);
  biases_.reserve(kMaxNodes);
}

PoseGraph::~PoseGraph() = default;

std::size_t PoseGraph::add_node(const Pose2& initial_world) {
  if (poses_.size() == kMaxNodes) {
    throw std::length_error("pose graph: more than " + std::to_string(kMaxNodes) + " nodes");
  }
  poses_.push_back(initial_world.vector());  // within the reserved capacity: nothing moves
  biases_.push_back(0.0);                    // likewise
  fixed_.push_back(false);
  has_bias_.push_back(false);
  bias_fixed_.push_back(false);
  problem_->problem.AddParameterBlock(poses_.back().data(), 3);
  return poses_.size() - 1;
}

void PoseGraph::fix_node(std::size_t i) {
  problem_->problem.SetParameterBlockConstant(poses_.at(i).data());
  fixed_.at(i) = true;
}

void PoseGraph::hold_before(std::size_t first_free) {
  first_free = std::min(first_free, poses_.size());
  for (std::size_t i = first_free; i < held_before_; ++i) {
    if (!fixed_[i]) problem_->problem.SetParameterBlockVariable(poses_[i].data());
    if (has_bias_[i] && !bias_fixed_[i]) problem_->problem.SetParameterBlockVariable(&biases_[i]);
  }
  for (std::size_t i = held_before_; i < first_free; ++i) {
    problem_->problem.SetParameterBlockConstant(poses_[i].data());
    if (has_bias_[i]) problem_->problem.SetParameterBlockConstant(&biases_[i]);
  }
  held_before_ = first_free;
}

void PoseGraph::add_prior(std::size_t i, const GaussianPose2& z_world) {
  double* pose = poses_.at(i).data();
  problem_->problem.AddResidualBlock(new PriorCost(z_world.mean, whitening(z_world.cov)), nullptr,
                                     pose);
}

void PoseGraph::add_relative(std::size_t i, std::size_t j, const GaussianPose2& z,
                             const Eigen::MatrixXd& observed, bool robust) {
  const Eigen::MatrixXd S = observed * z.cov * observed.transpose();
  double *pose_i = poses_.at(i).data(), *pose_j = poses_.at(j).data();  // checked first
  const Eigen::MatrixXd W = whitening(S) * observed;
  ceres::LossFunction* loss = nullptr;
  if (robust && config_.robust_scale_chi2 > 0.0) {
    if (config_.robust_loss == RobustLoss::kCauchy) {
      loss = new CauchyLoss(&problem_->c2);
    } else {
      loss = new DynamicCovarianceScalingLoss(&problem_->c2);
    }
  }
  const ceres::ResidualBlockId id =
      problem_->problem.AddResidualBlock(new RelativeCost(z.mean, W), loss, pose_i, pose_j);
  if (loss) problem_->robust.push_back(id);
}

void PoseGraph::add_heading(std::size_t i, double yaw_world_rad, double sigma_rad) {
  if (!(sigma_rad > 0.0)) throw std::invalid_argument("pose graph: heading sigma must be > 0");
  double* pose = poses_.at(i).data();
  problem_->problem.AddResidualBlock(new HeadingCost(yaw_world_rad, sigma_rad), nullptr, pose);
}

void PoseGraph::add_heading_bias(std::size_t i, double initial_rad, bool fixed) {
  if (has_bias_.at(i)) {
    throw std::invalid_argument("pose graph: node " + std::to_string(i) + " has a bias already");
  }
  biases_[i] = initial_rad;
  problem_->problem.AddParameterBlock(&biases_[i], 1);
  has_bias_[i] = true;
  bias_fixed_[i] = fixed;
  if (fixed || i < held_before_) problem_->problem.SetParameterBlockConstant(&biases_[i]);
}

double* PoseGraph::bias_block(std::size_t i) {
  if (!has_bias_.at(i)) {
    throw std::out_of_range("pose graph: node " + std::to_string(i) + " has no heading bias");
  }
  return &biases_[i];
}

void PoseGraph::add_heading_bias_prior(std::size_t i, double mean_rad, double sigma_rad) {
  if (!(sigma_rad > 0.0)) throw std::invalid_argument("pose graph: bias sigma must be > 0");
  double* bias = bias_block(i);
  problem_->problem.AddResidualBlock(new BiasPriorCost(mean_rad, sigma_rad), nullptr, bias);
}

void PoseGraph::add_heading_bias_walk(std::size_t i, std::size_t j, double sigma_rad) {
  if (!(sigma_rad > 0.0)) throw std::invalid_argument("pose graph: walk sigma must be > 0");
  double *bias_i = bias_block(i), *bias_j = bias_block(j);
  problem_->problem.AddResidualBlock(new BiasWalkCost(sigma_rad), nullptr, bias_i, bias_j);
}

void PoseGraph::add_biased_heading(std::size_t i, std::size_t bias_node, double yaw_world_rad,
                                   double sigma_rad) {
  if (!(sigma_rad > 0.0)) throw std::invalid_argument("pose graph: heading sigma must be > 0");
  double *pose = poses_.at(i).data(), *bias = bias_block(bias_node);
  problem_->problem.AddResidualBlock(new BiasedHeadingCost(yaw_world_rad, sigma_rad), nullptr, pose,
                                     bias);
}

double PoseGraph::heading_bias(std::size_t i) const {
  if (!has_bias_.at(i)) {
    throw std::out_of_range("pose graph: node " + std::to_string(i) + " has no heading bias");
  }
  return biases_[i];
}

void PoseGraph::set_heading_bias(std::size_t i, double bias_rad) { *bias_block(i) = bias_rad; }

PoseGraphSolve PoseGraph::solve(bool count_downweighted) {
  ceres::Solver::Options options;
  options.linear_solver_type = ceres::SPARSE_NORMAL_CHOLESKY;
  options.max_num_iterations = config_.max_iterations;
  options.num_threads = 1;  // runs are parallel across processes; the same bytes every time
  options.logging_type = ceres::SILENT;
  ceres::Solver::Summary summary;
  // Graduated start: first with the losses' scale widened, so that matches far from the current
  // (drifted) estimate still pull it their way, then at the configured scale.
  if (!problem_->robust.empty() && config_.robust_start_factor > 1.0) {
    problem_->c2 = config_.robust_scale_chi2 * config_.robust_start_factor;
    ceres::Solve(options, &problem_->problem, &summary);
  }
  problem_->c2 = config_.robust_scale_chi2;
  ceres::Solve(options, &problem_->problem, &summary);
  PoseGraphSolve out;
  out.converged = summary.termination_type == ceres::CONVERGENCE;
  out.final_cost = summary.final_cost;
  // Down-weighted: beyond the gate, a squared whitened norm above c^2.
  for (const ceres::ResidualBlockId id : problem_->robust) {
    if (!count_downweighted) break;  // a windowed online solve: counted at the smoothing solve
    double cost = 0.0;               // without the loss: half the squared norm
    problem_->problem.EvaluateResidualBlock(id, false, &cost, nullptr, nullptr);
    out.edges_downweighted += 2.0 * cost > config_.robust_scale_chi2;
  }
  // Keep the yaws wrapped, so that poses read back as the filters' do.
  for (Eigen::Vector3d& p : poses_) p(2) = normalize_angle(p(2));
  return out;
}

Pose2 PoseGraph::pose(std::size_t i) const { return Pose2(poses_.at(i)); }

const ceres::Problem& PoseGraph::problem_for_checks() const { return problem_->problem; }

namespace {

using Poses = std::vector<Eigen::Vector3d>;

/// The graph's information J^T J at the current estimate, over every edge (robust ones at their
/// weight there, as the solver sees them: Problem::Evaluate applies the losses), factored once by
/// Eigen's sparse Cholesky (AMD ordering), J's columns the free nodes in index order, then the
/// free heading-bias blocks in theirs. A fixed node's covariance blocks are zero.
///
/// Not ceres::Covariance: it orders its columns by the parameter blocks' addresses, and its
/// sparse QR (SuiteSparse over BLAS) gives other last bits with another memory layout, against
/// "same seed, same bytes" (docs/pose_graph.md). This depends only on the values.
class Information {
 public:
  Information(ceres::Problem& problem, Poses& poses, std::vector<double>& biases,
              const std::vector<bool>& has_bias)
      : problem_(problem), poses_(poses) {
    std::vector<double*> free_blocks;
    Eigen::Index columns = 0;
    column_.assign(poses.size(), -1);
    for (std::size_t i = 0; i < poses.size(); ++i) {
      if (problem.IsParameterBlockConstant(poses[i].data())) continue;
      column_[i] = columns;
      columns += 3;
      free_blocks.push_back(poses[i].data());
    }
    bias_column_.assign(poses.size(), -1);
    for (std::size_t i = 0; i < poses.size(); ++i) {
      if (!has_bias[i] || problem.IsParameterBlockConstant(&biases[i])) continue;
      bias_column_[i] = columns++;
      free_blocks.push_back(&biases[i]);
    }
    if (free_blocks.empty()) return;
    ceres::Problem::EvaluateOptions options;
    options.parameter_blocks = free_blocks;  // the other blocks are held constant
    options.num_threads = 1;
    ceres::CRSMatrix J;
    problem.Evaluate(options, nullptr, nullptr, nullptr, &J);
    const Eigen::Map<const Eigen::SparseMatrix<double, Eigen::RowMajor, int>> J_map(
        J.num_rows, J.num_cols, static_cast<Eigen::Index>(J.values.size()), J.rows.data(),
        J.cols.data(), J.values.data());
    llt_.compute(Eigen::SparseMatrix<double>(J_map.transpose() * J_map));
    singular_ = llt_.info() != Eigen::Success;
  }

  /// The joint marginal covariance of the heading biases of `bias_nodes`, then of the poses of
  /// `nodes` (b + 3n square, in that order): the information's inverse, solved for those columns
  /// only.
  Eigen::MatrixXd joint(const std::vector<std::size_t>& nodes,
                        const std::vector<std::size_t>& bias_nodes) const {
    for (const std::size_t i : nodes) {
      std::vector<ceres::ResidualBlockId> edges;
      problem_.GetResidualBlocksForParameterBlock(poses_.at(i).data(), &edges);
      if (edges.empty() && column_[i] >= 0) {
        throw std::runtime_error("pose graph: node " + std::to_string(i) + " has no edge");
      }
    }
    if (singular_) {
      throw std::runtime_error("pose graph: the covariance is singular (a node without a prior)");
    }
    // Each wanted row of the result: its column of the information (-1: held, zero covariance).
    std::vector<Eigen::Index> wanted;
    for (const std::size_t i : bias_nodes) wanted.push_back(bias_column_.at(i));
    for (const std::size_t i : nodes) {
      for (Eigen::Index r = 0; r < 3; ++r) wanted.push_back(column_[i] < 0 ? -1 : column_[i] + r);
    }
    const auto m = static_cast<Eigen::Index>(wanted.size());
    Eigen::MatrixXd C = Eigen::MatrixXd::Zero(m, m);
    if (llt_.rows() == 0) return C;
    Eigen::MatrixXd unit = Eigen::MatrixXd::Zero(llt_.rows(), m);
    for (Eigen::Index a = 0; a < m; ++a) {
      if (wanted[static_cast<std::size_t>(a)] >= 0)
        unit(wanted[static_cast<std::size_t>(a)], a) = 1;
    }
    const Eigen::MatrixXd solved = llt_.solve(unit);
    for (Eigen::Index a = 0; a < m; ++a) {
      if (wanted[static_cast<std::size_t>(a)] >= 0) {
        C.row(a) = solved.row(wanted[static_cast<std::size_t>(a)]);
      }
    }
    return 0.5 * (C + C.transpose());  // exactly symmetric
  }

 private:
  ceres::Problem& problem_;
  const Poses& poses_;
  std::vector<Eigen::Index> column_;       ///< a node's first pose column, -1 when held
  std::vector<Eigen::Index> bias_column_;  ///< its bias's column, -1 when none or held
  Eigen::SimplicialLLT<Eigen::SparseMatrix<double>> llt_;
  bool singular_ = false;
};

}  // namespace

std::vector<Eigen::Matrix3d> PoseGraph::covariances(const std::vector<std::size_t>& nodes) {
  hold_before(0);
  const Information information(problem_->problem, poses_, biases_, has_bias_);
  std::vector<Eigen::Matrix3d> out;
  // In batches: the joint of all nodes at once would be a dense 3N x 3N matrix.
  constexpr std::size_t kBatch = 64;
  for (std::size_t first = 0; first < nodes.size(); first += kBatch) {
    const std::vector<std::size_t> batch(
        nodes.begin() + static_cast<long>(first),
        nodes.begin() + static_cast<long>(std::min(first + kBatch, nodes.size())));
    const Eigen::MatrixXd joint = information.joint(batch, {});
    for (std::size_t k = 0; k < batch.size(); ++k) {
      out.emplace_back(
          joint.block<3, 3>(3 * static_cast<Eigen::Index>(k), 3 * static_cast<Eigen::Index>(k)));
    }
  }
  return out;
}

Eigen::MatrixXd PoseGraph::joint_covariance(const std::vector<std::size_t>& nodes,
                                            const std::vector<std::size_t>& bias_nodes) {
  hold_before(0);
  return Information(problem_->problem, poses_, biases_, has_bias_).joint(nodes, bias_nodes);
}

void PoseGraph::set_pose(std::size_t i, const Pose2& world) { poses_.at(i) = world.vector(); }

}  // namespace msislab
