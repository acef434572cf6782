#include "slam/linearisation_error.hpp"

#include <Eigen/Cholesky>
#include <cmath>
#include <limits>

namespace msislab {

double linearisation_error(const Deviation& deviation, const Eigen::VectorXd& x_hat,
                           const Eigen::MatrixXd& P, const Eigen::MatrixXd& J,
                           const Eigen::MatrixXd& C, int samples, std::mt19937_64& rng) {
  if (samples < 1) return std::numeric_limits<double>::quiet_NaN();
  // P = T^T L D L^T T (pivoted LDL^T, which takes a semi-definite P): x = x^ + T^T L D^1/2 xi.
  const Eigen::LDLT<Eigen::MatrixXd> ldlt(P);
  const Eigen::MatrixXd L = ldlt.matrixL();
  const Eigen::VectorXd sqrt_D = ldlt.vectorD().cwiseMax(0.0).cwiseSqrt();
  const Eigen::LLT<Eigen::MatrixXd> C_llt(C);
  std::normal_distribution<double> normal;
  Eigen::VectorXd xi(x_hat.size());
  double sum = 0.0;
  for (int s = 0; s < samples; ++s) {
    for (Eigen::Index i = 0; i < xi.size(); ++i) xi(i) = normal(rng);
    const Eigen::VectorXd dx = ldlt.transpositionsP().transpose() * (L * sqrt_D.cwiseProduct(xi));
    const Eigen::VectorXd e = deviation(x_hat + dx) - J * dx;
    sum += e.dot(C_llt.solve(e));
  }
  return sum / samples;
}

}  // namespace msislab
