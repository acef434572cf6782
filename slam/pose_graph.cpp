#include "slam/pose_graph.hpp"

#include <ceres/ceres.h>

#include <Eigen/Cholesky>
#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

#include "slam/pose_graph_edges.hpp"
#include "slam/pose_graph_problem.hpp"

namespace msislab {

namespace {

using pose_graph_edges::BiasWalkCost;
using pose_graph_edges::CauchyLoss;
using pose_graph_edges::CompassCost;
using pose_graph_edges::DynamicCovarianceScalingLoss;
using pose_graph_edges::MatchCost;
using pose_graph_edges::OdometryCost;
using pose_graph_edges::PriorCost;
using pose_graph_edges::RelativeCost;
using pose_graph_edges::ScalarPriorCost;

/// W with W S W^T = I for a positive definite S: the inverse of its lower Cholesky factor.
Eigen::MatrixXd whitening(const Eigen::MatrixXd& S) {
  const Eigen::LLT<Eigen::MatrixXd> llt(S);
  if (llt.info() != Eigen::Success) {
    throw std::invalid_argument("pose graph: an edge covariance is not positive definite");
  }
  return llt.matrixL().solve(Eigen::MatrixXd::Identity(S.rows(), S.cols()));
}

}  // namespace

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

void PoseGraph::hold_constants(bool held) {
  if (held == constants_held_) return;
  for (double* c : constant_blocks()) {
    if (held) {
      problem_->problem.SetParameterBlockConstant(c);
    } else {
      problem_->problem.SetParameterBlockVariable(c);
    }
  }
  constants_held_ = held;
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
  ceres::LossFunction* loss = robust_loss(robust);
  const ceres::ResidualBlockId id =
      problem_->problem.AddResidualBlock(new RelativeCost(z.mean, W), loss, pose_i, pose_j);
  if (loss) problem_->robust.push_back(id);
}

void PoseGraph::add_match(std::size_t i, std::size_t j, const GaussianPose2& z,
                          const Eigen::MatrixXd& observed, const Eigen::Vector3d& u_i,
                          const Eigen::Vector3d& u_j) {
  const Eigen::MatrixXd S = observed * z.cov * observed.transpose();
  std::vector<double*> blocks = {poses_.at(i).data(), poses_.at(j).data()};  // checked first
  const Eigen::MatrixXd W = whitening(S) * observed;
  const bool scale = has_constant(GraphConstant::kRangeScale);
  const bool clock = has_constant(GraphConstant::kClockOffset);
  if (scale) blocks.push_back(&constants_[index(GraphConstant::kRangeScale)]);
  if (clock) blocks.push_back(&constants_[index(GraphConstant::kClockOffset)]);
  ceres::LossFunction* loss = robust_loss(true);
  const ceres::ResidualBlockId id = problem_->problem.AddResidualBlock(
      new MatchCost(z.mean, W, scale, clock, u_i, u_j), loss, blocks);
  if (loss) problem_->robust.push_back(id);
}

ceres::LossFunction* PoseGraph::robust_loss(bool robust) {
  if (!robust || !(config_.robust_scale_chi2 > 0.0)) return nullptr;
  if (config_.robust_loss == RobustLoss::kCauchy) return new CauchyLoss(&problem_->c2);
  return new DynamicCovarianceScalingLoss(&problem_->c2);
}

void PoseGraph::add_constant(GraphConstant which, double initial, double prior_mean,
                             double prior_sigma) {
  if (has_constant(which)) throw std::invalid_argument("pose graph: that scale exists already");
  if (!(prior_sigma > 0.0)) throw std::invalid_argument("pose graph: scale sigma must be > 0");
  double* s = &constants_[index(which)];
  *s = initial;
  problem_->problem.AddParameterBlock(s, 1);
  problem_->problem.AddResidualBlock(new ScalarPriorCost(prior_mean, prior_sigma), nullptr, s);
  has_constant_[index(which)] = true;
  if (constants_held_) problem_->problem.SetParameterBlockConstant(s);
}

std::vector<double*> PoseGraph::constant_blocks() {
  std::vector<double*> out;
  for (std::size_t i = 0; i < constants_.size(); ++i) {
    if (has_constant_[i]) out.push_back(&constants_[i]);
  }
  return out;
}

bool PoseGraph::has_deviation() const {
  return has_constant(GraphConstant::kDeviationCos) && has_constant(GraphConstant::kDeviationSin);
}

void PoseGraph::append_deviation(std::vector<double*>& blocks) {
  blocks.push_back(&constants_[index(GraphConstant::kDeviationCos)]);
  blocks.push_back(&constants_[index(GraphConstant::kDeviationSin)]);
}

void PoseGraph::add_heading(std::size_t i, double yaw_world_rad, double sigma_rad) {
  if (!(sigma_rad > 0.0)) throw std::invalid_argument("pose graph: heading sigma must be > 0");
  std::vector<double*> blocks = {poses_.at(i).data()};
  if (has_deviation()) append_deviation(blocks);
  problem_->problem.AddResidualBlock(
      new CompassCost(yaw_world_rad, sigma_rad, false, has_deviation()), nullptr, blocks);
}

void PoseGraph::add_odometry(std::size_t i, std::size_t j, const GaussianPose2& z,
                             bool start_deviated) {
  const bool scale = has_constant(GraphConstant::kDvlScale);
  if (!scale && !has_deviation()) {
    add_relative(i, j, z, Eigen::Matrix3d::Identity(), false);
    return;
  }
  std::vector<double*> blocks = {poses_.at(i).data(), poses_.at(j).data()};  // checked first
  const Eigen::Matrix3d W = whitening(z.cov);
  if (scale) blocks.push_back(&constants_[index(GraphConstant::kDvlScale)]);
  if (has_deviation()) append_deviation(blocks);
  problem_->problem.AddResidualBlock(
      new OdometryCost(z.mean, W, scale, has_deviation(), start_deviated), nullptr, blocks);
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
  problem_->problem.AddResidualBlock(new ScalarPriorCost(mean_rad, sigma_rad), nullptr, bias);
}

void PoseGraph::add_heading_bias_walk(std::size_t i, std::size_t j, double sigma_rad) {
  if (!(sigma_rad > 0.0)) throw std::invalid_argument("pose graph: walk sigma must be > 0");
  double *bias_i = bias_block(i), *bias_j = bias_block(j);
  problem_->problem.AddResidualBlock(new BiasWalkCost(sigma_rad), nullptr, bias_i, bias_j);
}

void PoseGraph::add_biased_heading(std::size_t i, std::size_t bias_node, double yaw_world_rad,
                                   double sigma_rad) {
  if (!(sigma_rad > 0.0)) throw std::invalid_argument("pose graph: heading sigma must be > 0");
  std::vector<double*> blocks = {poses_.at(i).data(), bias_block(bias_node)};
  if (has_deviation()) append_deviation(blocks);
  problem_->problem.AddResidualBlock(
      new CompassCost(yaw_world_rad, sigma_rad, true, has_deviation()), nullptr, blocks);
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

void PoseGraph::set_pose(std::size_t i, const Pose2& world) { poses_.at(i) = world.vector(); }

}  // namespace msislab
