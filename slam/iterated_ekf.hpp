// The iterated EKF update of a state made of poses, optionally led by calibration parameters
// (paper Eq. 9-10), shared by trajectory SLAM's
// filters and the pose graph's per-scan belief (docs/trajectory_slam.md):
//   X_{i+1} = X^ + K_i (z - h(X_i) - H_i (X^ - X_i)),  K_i = P H_i^T (H_i P H_i^T + R)^-1,
// and then P = (I - K H) P at the last linearisation, which the caller applies (as the rank-d
// downdate P - K (P H^T)^T) to wherever its P lives.
#pragma once

#include <Eigen/Cholesky>
#include <Eigen/Core>
#include <algorithm>
#include <vector>

#include "geometry/se2.hpp"

namespace msislab {

/// Updates the `count` poses from `x` in place, after the additive parameters `parameters` (a
/// calibration, possibly empty) that lead the state: X = [parameters; poses]. P is X's covariance
/// (parameters.size() + 3 count square). residual(H) gives z (-) h at the current state and sets
/// H (d x X's size). at_first(x_prior, z_minus_h, innovation, S) is called at the first
/// linearisation; when it returns false (a gate) the state is left as it was and so is the result
/// false. K and PHt are those of the last linearisation, for the caller's downdate.
template <class Residual, class AtFirst>
bool iterated_ekf_update(Eigen::VectorXd& parameters, std::vector<Pose2>::iterator x,
                         std::size_t count, const Eigen::Ref<const Eigen::MatrixXd>& P,
                         const Residual& residual, const Eigen::MatrixXd& R, int iterations,
                         const AtFirst& at_first, Eigen::MatrixXd& K, Eigen::MatrixXd& PHt) {
  const Eigen::Index c = parameters.size();
  const auto m = static_cast<Eigen::Index>(c + 3 * static_cast<Eigen::Index>(count));
  const std::vector<Pose2> prior(x, x + static_cast<long>(count));
  const Eigen::VectorXd prior_parameters = parameters;
  Eigen::VectorXd x_prior(m);
  x_prior.head(c) = prior_parameters;
  for (std::size_t j = 0; j < count; ++j) {
    x_prior.segment<3>(c + static_cast<Eigen::Index>(3 * j)) = prior[j].vector();
  }
  Eigen::MatrixXd H;
  for (int iteration = 0; iteration < std::max(1, iterations); ++iteration) {
    const Eigen::VectorXd z_minus_h = residual(&H);
    Eigen::VectorXd dx(m);  // X^ - X_i, angles wrapped
    dx.head(c) = prior_parameters - parameters;
    for (std::size_t j = 0; j < count; ++j) {
      dx.segment<3>(c + static_cast<Eigen::Index>(3 * j)) = pose_difference(prior[j], x[j]);
    }
    // H is zero outside the columns of the poses h depends on: P H^T over those columns only.
    Eigen::Index first_col = 0, end_col = H.cols();
    while (first_col < end_col && H.col(first_col).isZero(0.0)) ++first_col;
    while (end_col > first_col && H.col(end_col - 1).isZero(0.0)) --end_col;
    PHt.noalias() = P.middleCols(first_col, end_col - first_col) *
                    H.middleCols(first_col, end_col - first_col).transpose();
    const Eigen::MatrixXd S = H * PHt + R;
    const Eigen::VectorXd innovation = z_minus_h - H * dx;
    if (iteration == 0 && !at_first(x_prior, z_minus_h, innovation, S)) return false;
    K.noalias() = S.ldlt().solve(PHt.transpose()).transpose();
    const Eigen::VectorXd x_new = x_prior + K * innovation;
    parameters = x_new.head(c);
    for (std::size_t j = 0; j < count; ++j) {
      x[j] = Pose2(Eigen::Vector3d(x_new.segment<3>(c + static_cast<Eigen::Index>(3 * j))));
    }
  }
  return true;
}

/// The same for a state of poses only.
template <class Residual, class AtFirst>
bool iterated_ekf_update(std::vector<Pose2>::iterator x, std::size_t count,
                         const Eigen::Ref<const Eigen::MatrixXd>& P, const Residual& residual,
                         const Eigen::MatrixXd& R, int iterations, const AtFirst& at_first,
                         Eigen::MatrixXd& K, Eigen::MatrixXd& PHt) {
  Eigen::VectorXd no_parameters;
  return iterated_ekf_update(no_parameters, x, count, P, residual, R, iterations, at_first, K, PHt);
}

}  // namespace msislab
