// The pose graph's information and the covariances read from it (PoseGraph::covariances,
// joint_covariance; docs/pose_graph.md): one sparse Cholesky factorisation of J^T J over the free
// nodes, heading biases and scale blocks.
#include <ceres/ceres.h>

#include <Eigen/SparseCholesky>
#include <Eigen/SparseCore>
#include <algorithm>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "slam/pose_graph.hpp"
#include "slam/pose_graph_problem.hpp"

namespace msislab {

namespace {

using Poses = std::vector<Eigen::Vector3d>;

/// The graph's information J^T J at the current estimate, over every edge (robust ones at their
/// weight there, as the solver sees them: Problem::Evaluate applies the losses), factored once by
/// Eigen's sparse Cholesky (AMD ordering), J's columns the free nodes in index order, then the
/// free heading-bias blocks in theirs, then the scale blocks. A fixed node's covariance blocks are
/// zero.
///
/// Not ceres::Covariance: it orders its columns by the parameter blocks' addresses, and its
/// sparse QR (SuiteSparse over BLAS) gives other last bits with another memory layout, against
/// "same seed, same bytes" (docs/pose_graph.md). This depends only on the values.
class Information {
 public:
  Information(ceres::Problem& problem, Poses& poses, std::vector<double>& biases,
              const std::vector<bool>& has_bias, const std::vector<double*>& scales)
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
    for (double* s : scales) {
      scale_column_.emplace_back(s, columns++);
      free_blocks.push_back(s);
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
                        const std::vector<std::size_t>& bias_nodes,
                        const std::vector<const double*>& scales) const {
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
    for (const double* s : scales) {
      for (const auto& [block, column] : scale_column_) {
        if (block == s) wanted.push_back(column);
      }
    }
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
  std::vector<std::pair<const double*, Eigen::Index>> scale_column_;  ///< each scale's column
  Eigen::SimplicialLLT<Eigen::SparseMatrix<double>> llt_;
  bool singular_ = false;
};

}  // namespace

std::vector<Eigen::Matrix3d> PoseGraph::covariances(const std::vector<std::size_t>& nodes) {
  hold_before(0);
  hold_constants(false);
  const Information information(problem_->problem, poses_, biases_, has_bias_, constant_blocks());
  std::vector<Eigen::Matrix3d> out;
  // In batches: the joint of all nodes at once would be a dense 3N x 3N matrix.
  constexpr std::size_t kBatch = 64;
  for (std::size_t first = 0; first < nodes.size(); first += kBatch) {
    const std::vector<std::size_t> batch(
        nodes.begin() + static_cast<long>(first),
        nodes.begin() + static_cast<long>(std::min(first + kBatch, nodes.size())));
    const Eigen::MatrixXd joint = information.joint(batch, {}, {});
    for (std::size_t k = 0; k < batch.size(); ++k) {
      out.emplace_back(
          joint.block<3, 3>(3 * static_cast<Eigen::Index>(k), 3 * static_cast<Eigen::Index>(k)));
    }
  }
  return out;
}

Eigen::MatrixXd PoseGraph::joint_covariance(const std::vector<std::size_t>& nodes,
                                            const std::vector<std::size_t>& bias_nodes,
                                            const std::vector<GraphConstant>& scales) {
  hold_before(0);
  hold_constants(false);
  std::vector<const double*> wanted;
  for (const GraphConstant which : scales) {
    if (!has_constant(which)) throw std::out_of_range("pose graph: no such scale");
    wanted.push_back(&constants_[index(which)]);
  }
  return Information(problem_->problem, poses_, biases_, has_bias_, constant_blocks())
      .joint(nodes, bias_nodes, wanted);
}

}  // namespace msislab
