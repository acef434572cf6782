// What the pose-graph SLAM knows of the nodes a scan touches while it adds the scan's edges: their
// means and joint covariance, updated edge by edge with the filters' iterated EKF
// (slam/iterated_ekf.hpp). Every edge a scan adds (odometry, compass, matches) involves only these
// nodes, so the EKF update of their joint gives their marginal in the grown graph, to first order,
// without solving the graph or factoring its information for each edge (docs/pose_graph.md).
#pragma once

#include <Eigen/Cholesky>
#include <Eigen/Core>
#include <limits>
#include <vector>

#include "geometry/gaussian_pose.hpp"
#include "slam/calibration_model.hpp"
#include "slam/iterated_ekf.hpp"

namespace msislab {

struct PoseGraphBelief {
  std::vector<std::size_t> nodes;  ///< graph node of each pose, in the covariance's order
  std::vector<Pose2> means;        ///< world frame
  Eigen::MatrixXd cov;             ///< joint, (p + 3n) square: the parameters, then the poses
  Eigen::Index newest = 0;         ///< the scan's own node, as an index into nodes
  /// Calibration leading the state (the newest node's heading bias, or none), as the filters'.
  Eigen::VectorXd parameters;

  /// The first row of the pose at index i in cov.
  Eigen::Index at(Eigen::Index i) const { return parameters.size() + 3 * i; }

  /// The pose of the newest node seen from the belief's node c, with its Jacobian H (3 x 3n).
  GaussianPose2 predict(Eigen::Index c, Eigen::MatrixXd* H) const {
    Eigen::Matrix3d J_c, J_t;
    const Pose2 h = means[c].between(means[newest], &J_c, &J_t);
    H->setZero(3, cov.cols());
    H->block<3, 3>(0, at(c)) = J_c;
    H->block<3, 3>(0, at(newest)) = J_t;
    const Eigen::Matrix3d P = *H * cov * H->transpose();
    return {h, 0.5 * (P + P.transpose())};
  }

  /// Appends node `node` as `previous (+) motion` (the odometry edge, Eq. 2), previous the index
  /// of the node the motion starts from; it becomes the newest. Exact for the marginal: nothing
  /// else touches the new node yet.
  void append_composed(std::size_t node, Eigen::Index previous, const GaussianPose2& motion) {
    append_relative(node, previous, motion);
    newest = static_cast<Eigen::Index>(nodes.size()) - 1;
  }

  /// Appends node `node` as `previous (+) x`, x = g.x the true motion behind the odometry's
  /// (slam/calibration_model.hpp: through the DVL's scale k, the parameter at index k_at, and the
  /// compass's deviation (a, b) at ab_at, ab_at + 1; -1: not in the belief). It becomes the
  /// newest.
  void append_calibrated(std::size_t node, Eigen::Index previous, const GaussianPose2& motion,
                         const CalibratedMotion& g, Eigen::Index k_at, Eigen::Index ab_at) {
    append_through(node, previous, motion, g, k_at, ab_at, false);
    newest = static_cast<Eigen::Index>(nodes.size()) - 1;
  }

  /// Appends node `node` as `from (+) r`, r = g.x or, backward (the motion runs from the new node
  /// to `from`), its inverse: J1+ on from's pose, J2+ dr/dk on k, J2+ dr/d(a, b) on (a, b), J2+
  /// dr/dm on the motion's noise (dr/d. = J- dx/d. backward). The newest stays the newest.
  void append_through(std::size_t node, Eigen::Index from, const GaussianPose2& motion,
                      const CalibratedMotion& g, Eigen::Index k_at, Eigen::Index ab_at,
                      bool backward) {
    Eigen::Matrix3d J_inverse = Eigen::Matrix3d::Identity();
    const Pose2 r = backward ? g.x.inverse(&J_inverse) : g.x;
    Eigen::Matrix3d J_from, J_relative;
    const Pose2 mean = means[from].compose(r, &J_from, &J_relative);
    const Eigen::Matrix3d J_r = backward ? Eigen::Matrix3d(J_relative * J_inverse) : J_relative;
    const Eigen::Index n = cov.rows();
    Eigen::MatrixXd G = Eigen::MatrixXd::Zero(3, n);  // d(new node)/d(belief)
    G.middleCols<3>(at(from)) = J_from;
    if (k_at >= 0) G.col(k_at) = J_r * g.d_k;
    if (ab_at >= 0) G.middleCols<2>(ab_at) = J_r * g.d_ab;
    const Eigen::MatrixXd cross = G * cov;
    const Eigen::Matrix3d P =
        cross * G.transpose() + J_r * g.d_m * motion.cov * g.d_m.transpose() * J_r.transpose();
    cov.conservativeResize(n + 3, n + 3);
    cov.bottomRows<3>().leftCols(n) = cross;
    cov.rightCols<3>().topRows(n) = cross.transpose();
    cov.bottomRightCorner<3, 3>() = 0.5 * (P + P.transpose());
    nodes.push_back(node);
    means.push_back(mean);
  }

  /// Drops (marginalises) the nodes at indices first..first + count - 1, after the newest.
  void drop(Eigen::Index first, Eigen::Index count) {
    std::vector<Eigen::Index> kept;
    for (Eigen::Index i = 0; i < static_cast<Eigen::Index>(nodes.size()); ++i) {
      if (i < first || i >= first + count) kept.push_back(i);
    }
    cov = marginal(kept);
    nodes.erase(nodes.begin() + first, nodes.begin() + first + count);
    means.erase(means.begin() + first, means.begin() + first + count);
  }

  /// Appends node `node` as `from (+) relative`, the relative pose independent of the belief:
  /// P_node = J1+ P_from J1+^T + J2+ P_relative J2+^T, its cross-covariances J1+ P_from,*. The
  /// newest stays the newest.
  void append_relative(std::size_t node, Eigen::Index from, const GaussianPose2& relative) {
    Eigen::Matrix3d J_from, J_relative;
    const Pose2 mean = means[from].compose(relative.mean, &J_from, &J_relative);
    const Eigen::Index n = cov.rows();
    cov.conservativeResize(n + 3, n + 3);
    cov.bottomRows<3>().leftCols(n) = J_from * cov.middleRows<3>(at(from)).leftCols(n);
    cov.rightCols<3>().topRows(n) = cov.bottomRows<3>().leftCols(n).transpose();
    const Eigen::Matrix3d P = J_from * cov.block<3, 3>(at(from), at(from)) * J_from.transpose() +
                              J_relative * relative.cov * J_relative.transpose();
    cov.bottomRightCorner<3, 3>() = 0.5 * (P + P.transpose());
    nodes.push_back(node);
    means.push_back(mean);
  }

  /// The marginal covariance of the node at index i.
  Eigen::Matrix3d node_cov(Eigen::Index i) const { return cov.block<3, 3>(at(i), at(i)); }

  /// The joint covariance of the parameters and the nodes at the given indices, in their order
  /// (the other nodes marginalised: their rows and columns dropped).
  Eigen::MatrixXd marginal(const std::vector<Eigen::Index>& kept) const {
    std::vector<Eigen::Index> rows;
    for (Eigen::Index r = 0; r < parameters.size(); ++r) rows.push_back(r);
    for (const Eigen::Index i : kept) {
      for (Eigen::Index r = 0; r < 3; ++r) rows.push_back(at(i) + r);
    }
    return cov(rows, rows);
  }

  /// Appends a node with its own covariance, uncorrelated with the others.
  void append_independent(std::size_t node, const GaussianPose2& x) {
    const Eigen::Index n = cov.rows();
    cov.conservativeResize(n + 3, n + 3);
    cov.bottomRows<3>().setZero();
    cov.rightCols<3>().setZero();
    cov.bottomRightCorner<3, 3>() = x.cov;
    nodes.push_back(node);
    means.push_back(x.mean);
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
    if (!iterated_ekf_update(parameters, means.begin(), means.size(), cov, residual, R, iterations,
                             gate, K, PHt)) {
      return false;
    }
    cov.noalias() -= K * PHt.transpose();
    cov = 0.5 * (cov + cov.transpose());
    return true;
  }
};

}  // namespace msislab
