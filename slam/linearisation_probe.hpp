// A study of trajectory SLAM's linearisations (docs/robocentric.md, slam/linearisation_error.hpp)
// as an observer: the filter tells it of each linearisation it makes (the function's deviation
// from its value at the linearisation point, the belief's covariance, the Jacobian it used and the
// covariance the result is measured in), and the probe measures epsilon there with its own random
// numbers. The filter's estimate is the same with a probe or without: the deviation evaluates the
// function on the probe's sample of the state, never on the filter's.
#pragma once

#include <Eigen/Core>
#include <array>
#include <cstddef>
#include <random>

#include "slam/linearisation_error.hpp"

namespace msislab {

/// The linearisations trajectory SLAM tells an observer of.
enum class Linearisation : std::size_t {
  kObservation,  ///< an accepted match update's h(X) at the prior, in the innovation covariance
  kInversion,    ///< a robocentric inversion (-)e_k (Eq. 11-13), in J- P J-^T
  kPose,  ///< after each step, the newest scan's pose in the start frame (the chain's read-out,
          ///< what NEES is scored with), in its propagated covariance
};
inline constexpr std::size_t kLinearisationKinds = 3;

class LinearisationObserver {
 public:
  virtual ~LinearisationObserver() = default;
  /// y = f(x) linearised at x_hat with Jacobian J, x's belief N(x_hat, P), y measured in C;
  /// deviation(x) = f(x) - f(x_hat) (angles wrapped).
  virtual void linearised(Linearisation kind, const Deviation& deviation,
                          const Eigen::VectorXd& x_hat, const Eigen::MatrixXd& P,
                          const Eigen::MatrixXd& J, const Eigen::MatrixXd& C) = 0;
};

/// epsilon of every linearisation, with `samples` draws each from the probe's own generator
/// (a fixed seed: the same run gives the same bytes), averaged per kind over the run.
class LinearisationProbe final : public LinearisationObserver {
 public:
  explicit LinearisationProbe(int samples) : samples_(samples) {}

  void linearised(Linearisation kind, const Deviation& deviation, const Eigen::VectorXd& x_hat,
                  const Eigen::MatrixXd& P, const Eigen::MatrixXd& J,
                  const Eigen::MatrixXd& C) override {
    tallies_[static_cast<std::size_t>(kind)].add(
        linearisation_error(deviation, x_hat, P, J, C, samples_, rng_));
  }
  const LinearisationTally& tally(Linearisation kind) const {
    return tallies_[static_cast<std::size_t>(kind)];
  }

 private:
  int samples_;
  std::mt19937_64 rng_{0x6c696e656172ULL};
  std::array<LinearisationTally, kLinearisationKinds> tallies_;
};

}  // namespace msislab
