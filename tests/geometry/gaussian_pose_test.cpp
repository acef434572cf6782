// Tests of the first-order covariance propagation of compounding and inversion
// (geometry/gaussian_pose.hpp): the result equals J P J^T with the pose Jacobians, stays symmetric
// and positive semi-definite, keeps zero covariance at zero, and matches a Monte Carlo estimate.
// Tolerances: J P J^T agreement to 1e-12 relative (analytic Jacobians) or 1e-6 relative
// (finite-difference Jacobians, step 1e-6); Monte Carlo covariance (200,000 samples, yaw sigma
// <= 0.03 rad so the linearisation holds) within 3% of sqrt(P_ii P_jj) per entry.
#include "geometry/gaussian_pose.hpp"

#include <gtest/gtest.h>

#include <Eigen/Cholesky>
#include <Eigen/Eigenvalues>
#include <cmath>
#include <functional>
#include <random>
#include <vector>
#include "geometry/angles.hpp"
#include "pose_jacobian.hpp"
#include "test_support.hpp"
#include "tests/draws.hpp"

namespace msislab {
namespace {

using testing::kFdStep;
using testing::numeric_jacobian;
constexpr int kMonteCarloSamples = 200000;
constexpr double kMonteCarloTol = 0.03;  ///< of sqrt(P_ii P_jj), per covariance entry

/// A random symmetric positive-definite covariance with standard deviations up to about
/// sigma_xy_m on x, y and sigma_yaw_rad on yaw, with random correlations.
Eigen::Matrix3d random_covariance(std::mt19937& rng, double sigma_xy_m, double sigma_yaw_rad) {
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  Eigen::Matrix3d A;
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 3; ++c) A(r, c) = unit(rng);
  const Eigen::Vector3d scale(sigma_xy_m, sigma_xy_m, sigma_yaw_rad);
  const Eigen::Matrix3d S = scale.asDiagonal() * A;
  return S * S.transpose() / 3.0 + 1e-3 * Eigen::Matrix3d(scale.cwiseAbs2().asDiagonal());
}

GaussianPose2 random_gaussian_pose(std::mt19937& rng) {
  std::uniform_real_distribution<double> xy_m(-10.0, 10.0);
  std::uniform_real_distribution<double> yaw_rad(-kPi, kPi);
  GaussianPose2 p;
  const double yaw = yaw_rad(rng), y = xy_m(rng), x = xy_m(rng);  // tests/draws.hpp's order
  p.mean = Pose2(x, y, yaw);
  p.cov = random_covariance(rng, 0.5, 0.2);
  return p;
}

double max_abs(const Eigen::Matrix3d& m) { return m.cwiseAbs().maxCoeff(); }

::testing::AssertionResult symmetric_psd(const Eigen::Matrix3d& P) {
  const double scale = std::max(max_abs(P), 1e-300);
  const double asymmetry = max_abs(P - P.transpose());
  if (asymmetry > 1e-14 * scale)
    return ::testing::AssertionFailure() << "asymmetry " << asymmetry << " in\n" << P;
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eig(P);
  if (eig.eigenvalues().minCoeff() < -1e-12 * scale)
    return ::testing::AssertionFailure() << "negative eigenvalue " << eig.eigenvalues().minCoeff();
  return ::testing::AssertionSuccess();
}

// ---------------------------------------------------------------------------------------------
// Covariance equals J P J^T

TEST(GaussianPose2, ComposeCovarianceIsJ1PJ1tPlusJ2PJ2t) {
  std::mt19937 rng(42);
  for (int i = 0; i < 200; ++i) {
    const GaussianPose2 x_ab = random_gaussian_pose(rng);
    const GaussianPose2 x_bc = random_gaussian_pose(rng);
    const GaussianPose2 x_ac = compose(x_ab, x_bc);

    Eigen::Matrix3d J1;
    Eigen::Matrix3d J2;
    const Pose2 mean = x_ab.mean.compose(x_bc.mean, &J1, &J2);
    EXPECT_EQ(x_ac.mean.vector(), mean.vector());
    const Eigen::Matrix3d expected =
        J1 * x_ab.cov * J1.transpose() + J2 * x_bc.cov * J2.transpose();
    EXPECT_LE(max_abs(x_ac.cov - expected), 1e-12 * max_abs(expected));

    // Independently of the analytic Jacobians: the same with finite-difference Jacobians.
    const Eigen::Matrix3d J1_fd =
        numeric_jacobian([&](const Pose2& p) { return p.compose(x_bc.mean); }, x_ab.mean);
    const Eigen::Matrix3d J2_fd =
        numeric_jacobian([&](const Pose2& p) { return x_ab.mean.compose(p); }, x_bc.mean);
    const Eigen::Matrix3d expected_fd =
        J1_fd * x_ab.cov * J1_fd.transpose() + J2_fd * x_bc.cov * J2_fd.transpose();
    EXPECT_LE(max_abs(x_ac.cov - expected_fd), 1e-6 * max_abs(expected_fd));
  }
}

TEST(GaussianPose2, InvertCovarianceIsJMinusPJMinusT) {
  std::mt19937 rng(43);
  for (int i = 0; i < 200; ++i) {
    const GaussianPose2 x_ab = random_gaussian_pose(rng);
    const GaussianPose2 x_ba = invert(x_ab);

    Eigen::Matrix3d J;
    const Pose2 mean = x_ab.mean.inverse(&J);
    EXPECT_EQ(x_ba.mean.vector(), mean.vector());
    const Eigen::Matrix3d expected = J * x_ab.cov * J.transpose();
    EXPECT_LE(max_abs(x_ba.cov - expected), 1e-12 * max_abs(expected));

    const Eigen::Matrix3d J_fd =
        numeric_jacobian([](const Pose2& p) { return p.inverse(); }, x_ab.mean);
    const Eigen::Matrix3d expected_fd = J_fd * x_ab.cov * J_fd.transpose();
    EXPECT_LE(max_abs(x_ba.cov - expected_fd), 1e-6 * max_abs(expected_fd));
  }
}

TEST(GaussianPose2, InvertThenComposeMatchesBetweenJacobians) {
  // (-)x_ab (+) x_ac through the two propagation steps equals one step with between's Jacobians.
  std::mt19937 rng(44);
  for (int i = 0; i < 50; ++i) {
    const GaussianPose2 x_ab = random_gaussian_pose(rng);
    const GaussianPose2 x_ac = random_gaussian_pose(rng);
    const GaussianPose2 x_bc = compose(invert(x_ab), x_ac);
    Eigen::Matrix3d J_ab;
    Eigen::Matrix3d J_ac;
    const Pose2 mean = x_ab.mean.between(x_ac.mean, &J_ab, &J_ac);
    const Eigen::Matrix3d expected =
        J_ab * x_ab.cov * J_ab.transpose() + J_ac * x_ac.cov * J_ac.transpose();
    EXPECT_LE(pose_difference(x_bc.mean, mean).cwiseAbs().maxCoeff(), 1e-12);
    EXPECT_LE(max_abs(x_bc.cov - expected), 1e-12 * max_abs(expected));
  }
}

TEST(GaussianPose2, BetweenCorrelatedPosesTakesOutWhatTheyShare) {
  // Independent poses: the same as inverting and composing. Two poses on one chain, x_ac =
  // x_ab (+) x_bc: the joint covariance of x_ab and x_ac gives back exactly x_bc's own
  // covariance, whatever x_ab's was.
  std::mt19937 rng(45);
  for (int i = 0; i < 50; ++i) {
    const GaussianPose2 x_ab = random_gaussian_pose(rng);
    const GaussianPose2 x_bc = random_gaussian_pose(rng);
    Eigen::Matrix<double, 6, 6> independent = Eigen::Matrix<double, 6, 6>::Zero();
    independent.topLeftCorner<3, 3>() = x_ab.cov;
    independent.bottomRightCorner<3, 3>() = x_bc.cov;
    const GaussianPose2 direct = compose(invert(x_ab), x_bc);
    const GaussianPose2 joint = between(x_ab.mean, x_bc.mean, independent);
    EXPECT_LE(pose_difference(joint.mean, direct.mean).cwiseAbs().maxCoeff(), 1e-12);
    EXPECT_LE(max_abs(joint.cov - direct.cov), 1e-12 * max_abs(direct.cov));

    Eigen::Matrix3d J1;
    Eigen::Matrix3d J2;
    const Pose2 x_ac = x_ab.mean.compose(x_bc.mean, &J1, &J2);
    Eigen::Matrix<double, 6, 6> chain;
    chain << x_ab.cov, x_ab.cov * J1.transpose(), J1 * x_ab.cov,
        J1 * x_ab.cov * J1.transpose() + J2 * x_bc.cov * J2.transpose();
    const GaussianPose2 back = between(x_ab.mean, x_ac, chain);
    EXPECT_LE(pose_difference(back.mean, x_bc.mean).cwiseAbs().maxCoeff(), 1e-9);
    EXPECT_LE(max_abs(back.cov - x_bc.cov), 1e-9 * max_abs(x_bc.cov));
  }
}

TEST(GaussianPose2, ClosedFormYawUncertaintyBecomesLateralUncertainty) {
  // Heading error sigma on x_ab = [0, 0, 0] moves a point d ahead by d * sigma sideways (y).
  const double sigma_yaw_rad = 0.01;
  const double d_m = 10.0;
  GaussianPose2 x_ab;
  x_ab.cov(2, 2) = sigma_yaw_rad * sigma_yaw_rad;
  GaussianPose2 x_bc;
  x_bc.mean = Pose2(d_m, 0.0, 0.0);
  const GaussianPose2 x_ac = compose(x_ab, x_bc);
  Eigen::Matrix3d expected = Eigen::Matrix3d::Zero();
  expected(1, 1) = d_m * d_m * sigma_yaw_rad * sigma_yaw_rad;
  expected(1, 2) = expected(2, 1) = d_m * sigma_yaw_rad * sigma_yaw_rad;
  expected(2, 2) = sigma_yaw_rad * sigma_yaw_rad;
  EXPECT_LE(max_abs(x_ac.cov - expected), 1e-18);

  // The inverse of a pose at the origin with yaw noise only: x_ba = [0, 0, -yaw], same variance.
  const GaussianPose2 x_ba = invert(x_ab);
  EXPECT_LE(max_abs(x_ba.cov - x_ab.cov), 1e-18);
}

// ---------------------------------------------------------------------------------------------
// Zero covariance, symmetry

TEST(GaussianPose2, ZeroCovarianceStaysZero) {
  std::mt19937 rng(45);
  for (int i = 0; i < 50; ++i) {
    GaussianPose2 x_ab = random_gaussian_pose(rng);
    GaussianPose2 x_bc = random_gaussian_pose(rng);
    x_ab.cov.setZero();
    x_bc.cov.setZero();
    EXPECT_EQ(compose(x_ab, x_bc).cov, Eigen::Matrix3d::Zero());
    EXPECT_EQ(invert(x_ab).cov, Eigen::Matrix3d::Zero());
  }
  EXPECT_EQ(GaussianPose2().cov, Eigen::Matrix3d::Zero());
}

TEST(GaussianPose2, OneCertainOperandContributesNothing) {
  std::mt19937 rng(46);
  for (int i = 0; i < 50; ++i) {
    GaussianPose2 x_ab = random_gaussian_pose(rng);
    GaussianPose2 x_bc = random_gaussian_pose(rng);
    Eigen::Matrix3d J1;
    Eigen::Matrix3d J2;
    x_ab.mean.compose(x_bc.mean, &J1, &J2);
    const Eigen::Matrix3d P_ab = x_ab.cov;
    x_ab.cov.setZero();
    EXPECT_LE(max_abs(compose(x_ab, x_bc).cov - J2 * x_bc.cov * J2.transpose()), 1e-15);
    x_ab.cov = P_ab;
    x_bc.cov.setZero();
    EXPECT_LE(max_abs(compose(x_ab, x_bc).cov - J1 * x_ab.cov * J1.transpose()), 1e-12);
  }
}

TEST(GaussianPose2, ResultIsSymmetricPositiveSemiDefinite) {
  std::mt19937 rng(47);
  for (int i = 0; i < 200; ++i) {
    const GaussianPose2 x_ab = random_gaussian_pose(rng);
    const GaussianPose2 x_bc = random_gaussian_pose(rng);
    EXPECT_TRUE(symmetric_psd(compose(x_ab, x_bc).cov));
    EXPECT_TRUE(symmetric_psd(invert(x_ab).cov));
    EXPECT_TRUE(symmetric_psd(compose(invert(x_ab), compose(x_ab, x_bc)).cov));
  }
}

// ---------------------------------------------------------------------------------------------
// Monte Carlo: sample covariance of the nonlinear map vs the propagated covariance

/// Draws x ~ N(mean, cov) in [x, y, yaw] (the yaw is wrapped by the Pose2 constructor).
class PoseSampler {
 public:
  explicit PoseSampler(const GaussianPose2& p)
      : mean_(p.mean.vector()), L_(p.cov.llt().matrixL()) {}
  Pose2 operator()(std::mt19937& rng) {
    const Eigen::Vector3d z = draws_last_first<3>([&] { return normal_(rng); });
    return Pose2(mean_ + L_ * z);
  }

 private:
  Eigen::Vector3d mean_;
  Eigen::Matrix3d L_;
  std::normal_distribution<double> normal_;
};

/// Sample mean offset and sample covariance of f(samples) around the propagated mean; the
/// deviations go through pose_difference so a yaw that wraps across +-pi is handled.
struct SampleMoments {
  Eigen::Vector3d mean_offset = Eigen::Vector3d::Zero();  ///< sample mean - propagated mean
  Eigen::Matrix3d cov = Eigen::Matrix3d::Zero();
};

SampleMoments sample_moments(const std::function<Pose2(std::mt19937&)>& draw,
                             const Pose2& propagated_mean, std::mt19937& rng) {
  std::vector<Eigen::Vector3d> deviations(kMonteCarloSamples);
  SampleMoments m;
  for (auto& d : deviations) {
    d = pose_difference(draw(rng), propagated_mean);
    m.mean_offset += d;
  }
  m.mean_offset /= kMonteCarloSamples;
  for (const auto& d : deviations) {
    const Eigen::Vector3d centred = d - m.mean_offset;
    m.cov += centred * centred.transpose();
  }
  m.cov /= kMonteCarloSamples - 1;
  return m;
}

::testing::AssertionResult covariance_matches(const SampleMoments& sample,
                                              const Eigen::Matrix3d& propagated) {
  const Eigen::Vector3d sigma = propagated.diagonal().cwiseSqrt();
  const Eigen::Matrix3d normalized_error =
      (sample.cov - propagated).cwiseQuotient(sigma * sigma.transpose());
  const Eigen::Vector3d normalized_bias = sample.mean_offset.cwiseQuotient(sigma);
  if (normalized_error.cwiseAbs().maxCoeff() <= kMonteCarloTol &&
      normalized_bias.cwiseAbs().maxCoeff() <= kMonteCarloTol)
    return ::testing::AssertionSuccess();
  return ::testing::AssertionFailure()
         << "error / sqrt(P_ii P_jj):\n"
         << normalized_error << "\nmean offset / sigma: " << normalized_bias.transpose()
         << "\nsample:\n"
         << sample.cov << "\npropagated:\n"
         << propagated;
}

/// Small noise (yaw sigma 0.02-0.03 rad) so the first-order propagation is accurate; the means
/// sit near yaw = pi so samples and results wrap.
GaussianPose2 monte_carlo_x_ab() {
  GaussianPose2 p;
  p.mean = Pose2(2.0, -1.0, kPi - 0.01);
  p.cov << 0.09, 0.02, 0.002, 0.02, 0.04, -0.001, 0.002, -0.001, 0.0004;
  return p;
}

GaussianPose2 monte_carlo_x_bc() {
  GaussianPose2 p;
  p.mean = Pose2(5.0, 2.0, 0.1);
  p.cov << 0.01, -0.004, 0.0, -0.004, 0.0225, 0.001, 0.0, 0.001, 0.0009;
  return p;
}

TEST(GaussianPose2MonteCarlo, ComposeMatchesSampleCovariance) {
  const GaussianPose2 x_ab = monte_carlo_x_ab();
  const GaussianPose2 x_bc = monte_carlo_x_bc();
  const GaussianPose2 x_ac = compose(x_ab, x_bc);
  PoseSampler sample_ab(x_ab);
  PoseSampler sample_bc(x_bc);
  std::mt19937 rng(testing::seed(2024));
  const SampleMoments moments = sample_moments(
      [&](std::mt19937& g) {
        const Pose2 a = sample_ab(g);
        return a.compose(sample_bc(g));
      },
      x_ac.mean, rng);
  EXPECT_TRUE(covariance_matches(moments, x_ac.cov));
}

TEST(GaussianPose2MonteCarlo, InvertMatchesSampleCovariance) {
  const GaussianPose2 x_ab = monte_carlo_x_ab();
  const GaussianPose2 x_ba = invert(x_ab);
  PoseSampler sample_ab(x_ab);
  std::mt19937 rng(testing::seed(2025));
  const SampleMoments moments =
      sample_moments([&](std::mt19937& g) { return sample_ab(g).inverse(); }, x_ba.mean, rng);
  EXPECT_TRUE(covariance_matches(moments, x_ba.cov));
}

}  // namespace
}  // namespace msislab
