// Direct measurement of the linearisation error an EKF commits (docs/robocentric.md):
// for a function f linearised at x^ with Jacobian J, and x ~ N(x^, P) the filter's belief, the
// part of f the linearisation leaves out,
//     e(x) = f(x) - f(x^) - J (x - x^)          (differences on angles wrapped),
// measured in the covariance C of the quantity f feeds (the innovation covariance of a match,
// the propagated covariance of an inversion or of a chain):
//     epsilon = E[e^T C^-1 e]    (Monte Carlo over seeded samples of x).
// epsilon is 0 for a linear f. It is the mean squared Mahalanobis size of what the first-order
// terms miss: next to a consistent NEES or NIS of about the dimension (3), an epsilon of 0.01 is
// a 0.3 % change; of 1, a third.
#pragma once

#include <Eigen/Core>
#include <functional>
#include <optional>
#include <random>

namespace msislab {

/// The deviation f(x) - f(x^) of a function from its value at the linearisation point, with its
/// angles wrapped (the caller knows which outputs are angles).
using Deviation = std::function<Eigen::VectorXd(const Eigen::VectorXd& x)>;

/// epsilon = E[e^T C^-1 e] over `samples` draws x = x^ + L xi (P = L L^T from a pivoted LDL^T,
/// so a semi-definite P works; xi standard normal from rng), with
/// e = deviation(x) - J (x - x^). C must be positive definite. NaN when samples < 1.
double linearisation_error(const Deviation& deviation, const Eigen::VectorXd& x_hat,
                           const Eigen::MatrixXd& P, const Eigen::MatrixXd& J,
                           const Eigen::MatrixXd& C, int samples, std::mt19937_64& rng);

/// A running mean of epsilon over the linearisations of one kind in a run.
struct LinearisationTally {
  double sum = 0.0;
  int count = 0;
  void add(double epsilon) {
    sum += epsilon;
    ++count;
  }
  std::optional<double> mean() const {
    return count > 0 ? std::optional<double>(sum / count) : std::nullopt;
  }
};

}  // namespace msislab
