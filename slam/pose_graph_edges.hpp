// The pose graph's edges as Ceres cost functions with analytic Jacobians (slam/pose_graph.hpp
// lists their residuals) and the robust losses on match edges. Internal to slam/pose_graph.cpp.
#pragma once

#include <ceres/ceres.h>

#include <Eigen/Core>
#include <cmath>
#include <cstdint>
#include <vector>

#include "geometry/se2.hpp"
#include "slam/calibration_model.hpp"

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
/// h (+) (tau u_j) (u_i, u_j the scans' velocities; slam/calibration_model.hpp), h_s = (s t, yaw)
/// of h_tau, r = W A (z (-) h_s). Blocks: x_i, x_j, then s, then tau. D = diag(s, s, 1) on
/// dh_tau/dh and dh_tau/dtau; dh_s/ds = (t_tau, 0).
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
      const ClockShifted shifted = clock_shifted(h, parameters[tau_block][0], u_i_, u_j_);
      h = shifted.h;
      dh = shifted.d_h;
      dtau = shifted.d_tau;
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

/// The compass, through its bias beta and its deviation (a, b) where the graph has them:
/// r = (yaw_z - psi - beta - a cos(psi) - b sin(psi)) / sigma, wrapped, psi = yaw_i. Blocks: x_i,
/// then beta, then a, b (scalars). dr/dx_i = [0, 0, -(1 - a sin(psi) + b cos(psi)) / sigma],
/// dr/dbeta = -1 / sigma, dr/da = -cos(psi) / sigma, dr/db = -sin(psi) / sigma.
class CompassCost : public ceres::CostFunction {
 public:
  CompassCost(double yaw_rad, double sigma_rad, bool bias, bool deviation)
      : yaw_rad_(yaw_rad), sigma_rad_(sigma_rad), bias_(bias), deviation_(deviation) {
    set_num_residuals(1);
    std::vector<int32_t>& sizes = *mutable_parameter_block_sizes();
    sizes = {3};
    if (bias) sizes.push_back(1);
    if (deviation) sizes.insert(sizes.end(), {1, 1});
  }

  bool Evaluate(double const* const* parameters, double* residuals,
                double** jacobians) const override {
    const double psi = parameters[0][2];
    const int a_block = bias_ ? 2 : 1;
    double r = yaw_rad_ - psi;
    if (bias_) r -= parameters[1][0];
    double slope = 0.0;  // d(deviation)/d(psi)
    if (deviation_) {
      const double a = parameters[a_block][0], b = parameters[a_block + 1][0];
      r -= a * std::cos(psi) + b * std::sin(psi);
      slope = -a * std::sin(psi) + b * std::cos(psi);
    }
    residuals[0] = normalize_angle(r) / sigma_rad_;
    if (!jacobians) return true;
    if (jacobians[0]) {
      jacobians[0][0] = 0.0;
      jacobians[0][1] = 0.0;
      jacobians[0][2] = -(1.0 + slope) / sigma_rad_;
    }
    if (bias_ && jacobians[1]) jacobians[1][0] = -1.0 / sigma_rad_;
    if (deviation_ && jacobians[a_block]) jacobians[a_block][0] = -std::cos(psi) / sigma_rad_;
    if (deviation_ && jacobians[a_block + 1]) {
      jacobians[a_block + 1][0] = -std::sin(psi) / sigma_rad_;
    }
    return true;
  }

 private:
  double yaw_rad_;
  double sigma_rad_;
  bool bias_, deviation_;
};

/// An odometry edge through the DVL's scale k and the compass's deviation (a, b) where the graph
/// has them (the filters' motion model read backwards, slam/calibration_model.hpp): the measured
/// motion of the true one h = (-)x_i (+) x_j is m = (k R(delta / 2) t_h, yaw_h + delta), delta =
/// a (cos psi_j - c cos psi_i) + b (sin psi_j - c sin psi_i) at the nodes' yaws, c = 1, or 0 when
/// node i's heading was not read from the compass (an exact start); r = W (z (-) m). Blocks: x_i,
/// x_j, then k, then a, b. With R = R(delta / 2), J the quarter turn and J_i, J_j of between():
/// dm/dh = diag(k R, 1), dm/dk = (R t_h, 0), dm/ddelta = (k J R t_h / 2, 1), and delta's own
/// derivatives over a, b and the two yaws.
class OdometryCost : public ceres::CostFunction {
 public:
  OdometryCost(const Pose2& z, const Eigen::Matrix3d& W, bool scale, bool deviation,
               bool start_deviated)
      : z_(z), W_(W), scale_(scale), deviation_(deviation), c_(start_deviated ? 1.0 : 0.0) {
    set_num_residuals(3);
    std::vector<int32_t>& sizes = *mutable_parameter_block_sizes();
    sizes = {3, 3};
    if (scale) sizes.push_back(1);
    if (deviation) sizes.insert(sizes.end(), {1, 1});
  }

  bool Evaluate(double const* const* parameters, double* residuals,
                double** jacobians) const override {
    const Pose2 x_i(parameters[0][0], parameters[0][1], parameters[0][2]);
    const Pose2 x_j(parameters[1][0], parameters[1][1], parameters[1][2]);
    const double k = scale_ ? parameters[2][0] : 1.0;
    const int a_block = scale_ ? 3 : 2;
    Eigen::Matrix3d J_i, J_j;
    const Pose2 h = x_i.between(x_j, &J_i, &J_j);
    // delta and its gradient over (a, b) and over (psi_i, psi_j).
    Eigen::Vector2d d_ab = Eigen::Vector2d::Zero(), d_psi = Eigen::Vector2d::Zero();
    double delta = 0.0;
    if (deviation_) {
      const double a = parameters[a_block][0], b = parameters[a_block + 1][0];
      const double psi_i = x_i.yaw(), psi_j = x_j.yaw();
      d_ab << std::cos(psi_j) - c_ * std::cos(psi_i), std::sin(psi_j) - c_ * std::sin(psi_i);
      d_psi << c_ * (a * std::sin(psi_i) - b * std::cos(psi_i)),
          -a * std::sin(psi_j) + b * std::cos(psi_j);
      delta = a * d_ab(0) + b * d_ab(1);
    }
    Eigen::Matrix2d R, J_turn;  // R(delta / 2)
    R << std::cos(delta / 2.0), -std::sin(delta / 2.0), std::sin(delta / 2.0),
        std::cos(delta / 2.0);
    J_turn << 0.0, -1.0, 1.0, 0.0;
    const Eigen::Vector2d turned = R * h.translation();
    const Pose2 m(k * turned.x(), k * turned.y(), h.yaw() + delta);
    Eigen::Map<Eigen::Vector3d> r(residuals);
    r = W_ * pose_difference(z_, m);
    if (!jacobians) return true;
    Eigen::Matrix3d dm_dh = Eigen::Matrix3d::Identity();
    dm_dh.topLeftCorner<2, 2>() = k * R;
    Eigen::Vector3d dm_ddelta;
    dm_ddelta << 0.5 * k * J_turn * turned, 1.0;
    for (int b = 0; b < 2; ++b) {
      if (!jacobians[b]) continue;
      Eigen::Matrix3d dm = dm_dh * (b == 0 ? J_i : J_j);
      dm.col(2) += dm_ddelta * d_psi(b);
      Eigen::Map<Eigen::Matrix<double, 3, 3, Eigen::RowMajor>> J(jacobians[b]);
      J = -W_ * dm;
    }
    if (scale_ && jacobians[2]) {
      Eigen::Map<Eigen::Vector3d> J(jacobians[2]);
      J = -W_ * Eigen::Vector3d(turned.x(), turned.y(), 0.0);
    }
    for (int e = 0; deviation_ && e < 2; ++e) {
      if (jacobians[a_block + e]) {
        Eigen::Map<Eigen::Vector3d> J(jacobians[a_block + e]);
        J = -W_ * dm_ddelta * d_ab(e);
      }
    }
    return true;
  }

 private:
  Pose2 z_;
  Eigen::Matrix3d W_;
  bool scale_, deviation_;
  double c_;
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
