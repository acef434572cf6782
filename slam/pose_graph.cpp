#include "slam/pose_graph.hpp"

#include <ceres/ceres.h>

#include <Eigen/Cholesky>
#include <Eigen/SparseCholesky>
#include <Eigen/SparseCore>
#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

namespace msislab {

namespace {

/// W with W S W^T = I for a positive definite S: the inverse of its lower Cholesky factor.
Eigen::MatrixXd whitening(const Eigen::MatrixXd& S) {
  const Eigen::LLT<Eigen::MatrixXd> llt(S);
  if (llt.info() != Eigen::Success) {
    throw std::invalid_argument("pose graph: an edge covariance is not positive definite");
  }
  return llt.matrixL().solve(Eigen::MatrixXd::Identity(S.rows(), S.cols()));
}

/// r = W A (z (-) ((-)x_i (+) x_j)); dr/dx_i = -W A J_i, dr/dx_j = -W A J_j with J_i, J_j the
/// Jacobians of between().
class RelativeCost : public ceres::CostFunction {
 public:
  RelativeCost(const Pose2& z, const Eigen::MatrixXd& WA) : z_(z), WA_(WA) {
    set_num_residuals(static_cast<int>(WA.rows()));
    mutable_parameter_block_sizes()->assign({3, 3});
  }

  bool Evaluate(double const* const* parameters, double* residuals,
                double** jacobians) const override {
    const Pose2 x_i(parameters[0][0], parameters[0][1], parameters[0][2]);
    const Pose2 x_j(parameters[1][0], parameters[1][1], parameters[1][2]);
    Eigen::Matrix3d J_i, J_j;
    const Pose2 h = x_i.between(x_j, &J_i, &J_j);
    const Eigen::Index d = WA_.rows();
    Eigen::Map<Eigen::VectorXd> r(residuals, d);
    r = WA_ * pose_difference(z_, h);
    if (jacobians) {
      for (int b = 0; b < 2; ++b) {
        if (!jacobians[b]) continue;
        Eigen::Map<Eigen::Matrix<double, Eigen::Dynamic, 3, Eigen::RowMajor>> J(jacobians[b], d, 3);
        J = -WA_ * (b == 0 ? J_i : J_j);
      }
    }
    return true;
  }

 private:
  Pose2 z_;
  Eigen::MatrixXd WA_;
};

/// r = W (z (-) x_i); dr/dx_i = -W.
class PriorCost : public ceres::SizedCostFunction<3, 3> {
 public:
  PriorCost(const Pose2& z, const Eigen::Matrix3d& W) : z_(z), W_(W) {}

  bool Evaluate(double const* const* parameters, double* residuals,
                double** jacobians) const override {
    const Pose2 x(parameters[0][0], parameters[0][1], parameters[0][2]);
    Eigen::Map<Eigen::Vector3d> r(residuals);
    r = W_ * pose_difference(z_, x);
    if (jacobians && jacobians[0]) {
      Eigen::Map<Eigen::Matrix<double, 3, 3, Eigen::RowMajor>> J(jacobians[0]);
      J = -W_;
    }
    return true;
  }

 private:
  Pose2 z_;
  Eigen::Matrix3d W_;
};

/// r = (yaw_z - yaw_i) / sigma, wrapped; dr/dx_i = [0, 0, -1 / sigma].
class HeadingCost : public ceres::SizedCostFunction<1, 3> {
 public:
  HeadingCost(double yaw_rad, double sigma_rad) : yaw_rad_(yaw_rad), sigma_rad_(sigma_rad) {}

  bool Evaluate(double const* const* parameters, double* residuals,
                double** jacobians) const override {
    residuals[0] = normalize_angle(yaw_rad_ - parameters[0][2]) / sigma_rad_;
    if (jacobians && jacobians[0]) {
      jacobians[0][0] = 0.0;
      jacobians[0][1] = 0.0;
      jacobians[0][2] = -1.0 / sigma_rad_;
    }
    return true;
  }

 private:
  double yaw_rad_;
  double sigma_rad_;
};

/// Dynamic covariance scaling's kernel: rho(s) = s for s <= c^2, else 3 c^2 - 4 c^4 / (c^2 + s)
/// (rho' = 4 c^4 / (c^2 + s)^2, rho'' = -8 c^4 / (c^2 + s)^3): continuous with its derivative at
/// the gate. c^2 is read from the graph at each evaluation (the graduated start changes it).
class DynamicCovarianceScalingLoss : public ceres::LossFunction {
 public:
  explicit DynamicCovarianceScalingLoss(const double* c2) : c2_(c2) {}
  void Evaluate(double s, double rho[3]) const override {
    const double c2 = *c2_;
    if (s <= c2) {
      rho[0] = s;
      rho[1] = 1.0;
      rho[2] = 0.0;
      return;
    }
    const double d = c2 + s;
    rho[0] = 3.0 * c2 - 4.0 * c2 * c2 / d;
    rho[1] = 4.0 * c2 * c2 / (d * d);
    rho[2] = -8.0 * c2 * c2 / (d * d * d);
  }

 private:
  const double* c2_;
};

/// Cauchy: rho(s) = c^2 log(1 + s / c^2), rho' = 1 / (1 + s / c^2), rho'' = -rho'^2 / c^2.
class CauchyLoss : public ceres::LossFunction {
 public:
  explicit CauchyLoss(const double* c2) : c2_(c2) {}
  void Evaluate(double s, double rho[3]) const override {
    const double c2 = *c2_;
    const double w = 1.0 / (1.0 + s / c2);
    rho[0] = c2 * std::log1p(s / c2);
    rho[1] = w;
    rho[2] = -w * w / c2;
  }

 private:
  const double* c2_;
};

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
}

PoseGraph::~PoseGraph() = default;

std::size_t PoseGraph::add_node(const Pose2& initial_world) {
  if (poses_.size() == kMaxNodes) {
    throw std::length_error("pose graph: more than " + std::to_string(kMaxNodes) + " nodes");
  }
  poses_.push_back(initial_world.vector());  // within the reserved capacity: nothing moves
  fixed_.push_back(false);
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
  }
  for (std::size_t i = held_before_; i < first_free; ++i) {
    problem_->problem.SetParameterBlockConstant(poses_[i].data());
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
/// Eigen's sparse Cholesky (AMD ordering), J's columns the free nodes in index order. A fixed
/// node's covariance blocks are zero.
///
/// Not ceres::Covariance: it orders its columns by the parameter blocks' addresses, and its
/// sparse QR (SuiteSparse over BLAS) gives other last bits with another memory layout, against
/// "same seed, same bytes" (docs/pose_graph.md). This depends only on the values.
class Information {
 public:
  Information(ceres::Problem& problem, Poses& poses) : problem_(problem), poses_(poses) {
    std::vector<double*> free_blocks;
    column_.assign(poses.size(), -1);
    for (std::size_t i = 0; i < poses.size(); ++i) {
      if (problem.IsParameterBlockConstant(poses[i].data())) continue;
      column_[i] = 3 * static_cast<Eigen::Index>(free_blocks.size());
      free_blocks.push_back(poses[i].data());
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

  /// The joint marginal covariance of `nodes` (3n x 3n, in that order): the information's
  /// inverse, solved for those nodes' columns only.
  Eigen::MatrixXd joint(const std::vector<std::size_t>& nodes) const {
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
    const auto n = static_cast<Eigen::Index>(nodes.size());
    Eigen::MatrixXd C = Eigen::MatrixXd::Zero(3 * n, 3 * n);
    if (llt_.rows() == 0) return C;
    Eigen::MatrixXd unit = Eigen::MatrixXd::Zero(llt_.rows(), 3 * n);
    for (Eigen::Index a = 0; a < n; ++a) {
      const Eigen::Index c = column_[nodes[static_cast<std::size_t>(a)]];
      if (c >= 0) unit.block<3, 3>(c, 3 * a).setIdentity();
    }
    const Eigen::MatrixXd solved = llt_.solve(unit);
    for (Eigen::Index a = 0; a < n; ++a) {
      const Eigen::Index c = column_[nodes[static_cast<std::size_t>(a)]];
      if (c >= 0) C.middleRows<3>(3 * a) = solved.middleRows<3>(c);
    }
    return 0.5 * (C + C.transpose());  // exactly symmetric
  }

 private:
  ceres::Problem& problem_;
  const Poses& poses_;
  std::vector<Eigen::Index> column_;
  Eigen::SimplicialLLT<Eigen::SparseMatrix<double>> llt_;
  bool singular_ = false;
};

}  // namespace

std::vector<Eigen::Matrix3d> PoseGraph::covariances(const std::vector<std::size_t>& nodes) {
  hold_before(0);
  const Information information(problem_->problem, poses_);
  std::vector<Eigen::Matrix3d> out;
  // In batches: the joint of all nodes at once would be a dense 3N x 3N matrix.
  constexpr std::size_t kBatch = 64;
  for (std::size_t first = 0; first < nodes.size(); first += kBatch) {
    const std::vector<std::size_t> batch(
        nodes.begin() + static_cast<long>(first),
        nodes.begin() + static_cast<long>(std::min(first + kBatch, nodes.size())));
    const Eigen::MatrixXd joint = information.joint(batch);
    for (std::size_t k = 0; k < batch.size(); ++k) {
      out.emplace_back(
          joint.block<3, 3>(3 * static_cast<Eigen::Index>(k), 3 * static_cast<Eigen::Index>(k)));
    }
  }
  return out;
}

Eigen::MatrixXd PoseGraph::joint_covariance(const std::vector<std::size_t>& nodes) {
  hold_before(0);
  return Information(problem_->problem, poses_).joint(nodes);
}

void PoseGraph::set_pose(std::size_t i, const Pose2& world) { poses_.at(i) = world.vector(); }

}  // namespace msislab
