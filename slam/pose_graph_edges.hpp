// The pose graph's edges as Ceres cost functions with analytic Jacobians (slam/pose_graph.hpp
// lists their residuals) and the robust losses on match edges. Internal to slam/pose_graph.cpp.
#pragma once

#include <ceres/ceres.h>

#include <Eigen/Core>
#include <cmath>
#include <cstdint>
#include <vector>

#include "geometry/se2.hpp"

namespace msislab::pose_graph_edges {

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

/// A match through the clock offset tau and the range scale s, each where the graph has it (the
/// filters' model, slam/trajectory_observations.cpp): h = (-)x_i (+) x_j, h_tau = (-)(tau u_i) (+)
/// h (+) (tau u_j) (u_i, u_j the scans' velocities), h_s = (s t, yaw) of h_tau, r = W A (z (-)
/// h_s). Blocks: x_i, x_j, then s, then tau. With J1, J2 of the outer composition, J1', J2' of the
/// inner one and J- of the inversion: dh_tau/dh = J1 J2', dh_tau/dtau = J1 J1' J- u_i + J2 u_j;
/// D = diag(s, s, 1) on both; dh_s/ds = (t_tau, 0). Without the clock it is the scaled edge of
/// PoseGraph::add_scaled_relative too (the DVL's scale k in place of s on an odometry edge).
class MatchCost : public ceres::CostFunction {
 public:
  MatchCost(const Pose2& z, const Eigen::MatrixXd& WA, bool scale, bool clock,
            const Eigen::Vector3d& u_i, const Eigen::Vector3d& u_j)
      : z_(z), WA_(WA), scale_(scale), clock_(clock), u_i_(u_i), u_j_(u_j) {
    set_num_residuals(static_cast<int>(WA.rows()));
    std::vector<int32_t>& sizes = *mutable_parameter_block_sizes();
    sizes = {3, 3};
    if (scale) sizes.push_back(1);
    if (clock) sizes.push_back(1);
  }

  bool Evaluate(double const* const* parameters, double* residuals,
                double** jacobians) const override {
    const Pose2 x_i(parameters[0][0], parameters[0][1], parameters[0][2]);
    const Pose2 x_j(parameters[1][0], parameters[1][1], parameters[1][2]);
    const double s = scale_ ? parameters[2][0] : 1.0;
    const int tau_block = scale_ ? 3 : 2;
    Eigen::Matrix3d J_i, J_j;
    Pose2 h = x_i.between(x_j, &J_i, &J_j);
    Eigen::Matrix3d dh = Eigen::Matrix3d::Identity();  // d(h_tau)/d(h)
    Eigen::Vector3d dtau = Eigen::Vector3d::Zero();    // d(h_tau)/d(tau)
    if (clock_) {
      const double tau = parameters[tau_block][0];
      Eigen::Matrix3d J_inverse, J1_inner, J2_inner, J1, J2;
      const Pose2 back = Pose2(Eigen::Vector3d(tau * u_i_)).inverse(&J_inverse);
      const Pose2 inner = back.compose(h, &J1_inner, &J2_inner);
      h = inner.compose(Pose2(Eigen::Vector3d(tau * u_j_)), &J1, &J2);
      dh = J1 * J2_inner;
      dtau = J1 * J1_inner * J_inverse * u_i_ + J2 * u_j_;
    }
    const Eigen::Matrix3d D = Eigen::Vector3d(s, s, 1.0).asDiagonal();
    const Pose2 h_s(s * h.x(), s * h.y(), h.yaw());
    const Eigen::Index d = WA_.rows();
    Eigen::Map<Eigen::VectorXd> r(residuals, d);
    r = WA_ * pose_difference(z_, h_s);
    if (!jacobians) return true;
    for (int b = 0; b < 2; ++b) {
      if (!jacobians[b]) continue;
      Eigen::Map<Eigen::Matrix<double, Eigen::Dynamic, 3, Eigen::RowMajor>> J(jacobians[b], d, 3);
      J = -WA_ * D * dh * (b == 0 ? J_i : J_j);
    }
    if (scale_ && jacobians[2]) {
      Eigen::Map<Eigen::VectorXd>(jacobians[2], d) = -WA_ * Eigen::Vector3d(h.x(), h.y(), 0.0);
    }
    if (clock_ && jacobians[tau_block]) {
      Eigen::Map<Eigen::VectorXd>(jacobians[tau_block], d) = -WA_ * D * dtau;
    }
    return true;
  }

 private:
  Pose2 z_;
  Eigen::MatrixXd WA_;
  bool scale_, clock_;
  Eigen::Vector3d u_i_, u_j_;
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

/// The compass through its bias: r = (yaw_z - yaw_i - b_i) / sigma, wrapped; dr/dx_i = [0, 0,
/// -1 / sigma], dr/db_i = -1 / sigma.
class BiasedHeadingCost : public ceres::SizedCostFunction<1, 3, 1> {
 public:
  BiasedHeadingCost(double yaw_rad, double sigma_rad) : yaw_rad_(yaw_rad), sigma_rad_(sigma_rad) {}

  bool Evaluate(double const* const* parameters, double* residuals,
                double** jacobians) const override {
    residuals[0] = normalize_angle(yaw_rad_ - parameters[0][2] - parameters[1][0]) / sigma_rad_;
    if (jacobians && jacobians[0]) {
      jacobians[0][0] = 0.0;
      jacobians[0][1] = 0.0;
      jacobians[0][2] = -1.0 / sigma_rad_;
    }
    if (jacobians && jacobians[1]) jacobians[1][0] = -1.0 / sigma_rad_;
    return true;
  }

 private:
  double yaw_rad_;
  double sigma_rad_;
};

/// The bias's random walk between two nodes: r = (b_j - b_i) / sigma; dr/db_i = -1 / sigma,
/// dr/db_j = 1 / sigma.
class BiasWalkCost : public ceres::SizedCostFunction<1, 1, 1> {
 public:
  explicit BiasWalkCost(double sigma_rad) : sigma_rad_(sigma_rad) {}

  bool Evaluate(double const* const* parameters, double* residuals,
                double** jacobians) const override {
    residuals[0] = (parameters[1][0] - parameters[0][0]) / sigma_rad_;
    if (jacobians && jacobians[0]) jacobians[0][0] = -1.0 / sigma_rad_;
    if (jacobians && jacobians[1]) jacobians[1][0] = 1.0 / sigma_rad_;
    return true;
  }

 private:
  double sigma_rad_;
};

/// A scalar's prior (a heading bias, the range scale): r = (b_i - z) / sigma; dr/db_i = 1 / sigma.
class ScalarPriorCost : public ceres::SizedCostFunction<1, 1> {
 public:
  ScalarPriorCost(double mean, double sigma) : mean_(mean), sigma_(sigma) {}

  bool Evaluate(double const* const* parameters, double* residuals,
                double** jacobians) const override {
    residuals[0] = (parameters[0][0] - mean_) / sigma_;
    if (jacobians && jacobians[0]) jacobians[0][0] = 1.0 / sigma_;
    return true;
  }

 private:
  double mean_;
  double sigma_;
};

}  // namespace msislab::pose_graph_edges
