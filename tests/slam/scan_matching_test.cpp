// spIC scan matching: recovery of a known relative pose from perturbed guesses, rejection of
// scans that do not overlap, point-to-line covariances, the short-motion bias of one-way
// association in a canal, and the cross-covariance of two matches that share their current scan
// against Monte Carlo.
#include "slam/scan_matching.hpp"

#include <gtest/gtest.h>

#include <Eigen/LU>
#include <cmath>
#include <iostream>
#include <random>

#include "scan_fixtures.hpp"
#include "test_support.hpp"
#include "tests/draws.hpp"

namespace msislab {
namespace {

using testing_scans::corner_walls;
using testing_scans::noisy;

TEST(ScanMatching, RecoversAKnownPoseFromPerturbedGuesses) {
  const Pose2 q_true(1.2, -0.6, 0.15);  // current frame in the reference frame
  std::mt19937 rng(testing::seed(3));
  const auto world = corner_walls();
  std::vector<Eigen::Vector2d> seen_from_current;
  for (const auto& p : world) seen_from_current.push_back(q_true.inverse().transform(p));
  int within_3_sigma = 0;
  const int trials = 40;
  std::normal_distribution<double> guess_noise(0.0, 1.0);
  for (int t = 0; t < trials; ++t) {
    const auto reference = noisy(world, 0.05, rng);
    const auto current = noisy(seen_from_current, 0.05, rng);
    GaussianPose2 guess;
    guess.cov = Eigen::Vector3d(0.4 * 0.4, 0.4 * 0.4, 0.08 * 0.08).asDiagonal();
    const Eigen::Vector3d g = draws_last_first<3>([&] { return guess_noise(rng); });
    guess.mean =
        Pose2(q_true.x() + 0.4 * g.x(), q_true.y() + 0.4 * g.y(), q_true.yaw() + 0.08 * g.z());
    const ScanMatchResult r = match_scans(reference, current, guess, ScanMatchConfig{});
    ASSERT_TRUE(r.valid) << "trial " << t;
    EXPECT_TRUE(r.converged) << "trial " << t;
    const Eigen::Vector3d e = pose_difference(r.estimate.mean, q_true);
    // Over 400 trials (10 seed offsets, stride 1000): the translation error's rms 0.013 m (about
    // 0.009 m an axis, as the match's own sd), at most 0.031 m; the yaw's rms 0.0008 rad, at most
    // 0.0025. The bounds sit at 5.4 and 6 standard deviations: a Rayleigh tail of 5e-7 a trial,
    // 2e-5 for the 40; a match 5 cm or 0.3 deg off is caught.
    EXPECT_LT(e.head<2>().norm(), 0.05) << "trial " << t;
    EXPECT_LT(std::abs(e(2)), 0.005) << "trial " << t;
    within_3_sigma += e.dot(r.estimate.cov.inverse() * e) < 14.16;  // chi2(3) 99.7%
  }
  EXPECT_GE(within_3_sigma, trials - 2);
}

TEST(ScanMatching, TooFewAssociationsIsNotValid) {
  std::mt19937 rng(1);
  const auto reference = noisy(corner_walls(), 0.05, rng);
  std::vector<Eigen::Vector2d> far_away;
  for (const auto& p : corner_walls()) far_away.push_back(p + Eigen::Vector2d(200.0, 0.0));
  const auto current = noisy(far_away, 0.05, rng);
  GaussianPose2 guess;
  guess.cov = 0.01 * Eigen::Matrix3d::Identity();
  EXPECT_FALSE(match_scans(reference, current, guess, ScanMatchConfig{}).valid);
  EXPECT_FALSE(match_scans(reference, {}, guess, ScanMatchConfig{}).valid);
}

/// A straight corridor: walls at y = +-8 m, sampled every 0.5 m over 40 m around the sensor at
/// x0 (the sampling moves with the sensor), and two bollards that alone fix the position along it.
std::vector<Eigen::Vector2d> corridor(double x0_m) {
  std::vector<Eigen::Vector2d> points;
  for (double s = -20.0; s <= 20.0; s += 0.5) {
    points.emplace_back(x0_m + s, 8.0);
    points.emplace_back(x0_m + s, -8.0);
  }
  points.emplace_back(4.0, 3.0);
  points.emplace_back(-6.0, -2.0);
  return points;
}

struct CovariancePair {
  Eigen::Matrix3d point_to_point, point_to_line;
};

CovariancePair corridor_or_room_covariances(bool corridor_scene, std::mt19937& rng) {
  const Pose2 q_true(1.5, 0.1, 0.02);
  std::vector<Eigen::Vector2d> world_ref, seen_from_current;
  if (corridor_scene) {
    world_ref = corridor(0.0);
    for (const auto& p : corridor(q_true.x()))
      seen_from_current.push_back(q_true.inverse().transform(p));
  } else {
    world_ref = corner_walls();
    for (const auto& p : world_ref) seen_from_current.push_back(q_true.inverse().transform(p));
  }
  const auto reference = noisy(world_ref, 0.05, rng);
  const auto current = noisy(seen_from_current, 0.05, rng);
  GaussianPose2 guess;
  guess.mean = q_true;
  guess.cov = Eigen::Vector3d(0.3 * 0.3, 0.3 * 0.3, 0.03 * 0.03).asDiagonal();
  ScanMatchConfig config;
  config.point_to_line_covariance = false;
  config.point_to_line_estimate = false;
  CovariancePair out;
  const ScanMatchResult p2p = match_scans(reference, current, guess, config);
  config.point_to_line_covariance = true;
  const ScanMatchResult p2l = match_scans(reference, current, guess, config);
  EXPECT_TRUE(p2p.valid && p2l.valid);
  out.point_to_point = p2p.estimate.cov;
  out.point_to_line = p2l.estimate.cov;
  return out;
}

TEST(ScanMatching, PointToLineCovarianceIsLargeAlongACorridor) {
  std::mt19937 rng(11);
  const CovariancePair c = corridor_or_room_covariances(true, rng);
  // Along the corridor (x) only the two bollards hold the match; point-to-point also counts the
  // walls' samples, which move with the sensor and say nothing about x.
  EXPECT_GT(c.point_to_line(0, 0), 10.0 * c.point_to_point(0, 0));
  EXPECT_GT(c.point_to_line(0, 0), 10.0 * c.point_to_line(1, 1));
  EXPECT_LT(c.point_to_line(1, 1), 2.0 * c.point_to_point(1, 1));
}

TEST(ScanMatching, PointToLineCovarianceStaysSmallInARoom) {
  std::mt19937 rng(12);
  const CovariancePair c = corridor_or_room_covariances(false, rng);
  for (int i = 0; i < 3; ++i) {
    EXPECT_LT(c.point_to_line(i, i), 3.0 * c.point_to_point(i, i)) << i;
  }
  // Not a statistic: the standard deviations the matcher reports, not errors drawn.
  EXPECT_LT(std::sqrt(c.point_to_line(0, 0)), 0.05);
  EXPECT_LT(std::sqrt(c.point_to_line(1, 1)), 0.05);
}

/// A canal along x: quays at y = +-5 m with a gentle waviness (what fixes the position along it),
/// sampled every 0.3 m in the world, of which a scan sees only the points within 12 m of its
/// sensor at (x0, 0).
std::vector<Eigen::Vector2d> canal_seen_from(double x0_m) {
  std::vector<Eigen::Vector2d> points;
  for (double x = -30.0; x <= 30.0; x += 0.3) {
    for (const Eigen::Vector2d& p : {Eigen::Vector2d(x, 5.0 + 0.4 * std::sin(x)),
                                     Eigen::Vector2d(x, -5.0 + 0.3 * std::cos(0.8 * x))}) {
      if ((p - Eigen::Vector2d(x0_m, 0.0)).norm() <= 12.0) points.push_back(p);
    }
  }
  return points;
}

/// Mean error along the canal of spIC started from the truth, over noisy trials.
double mean_along_canal_error_m(bool reciprocal) {
  const Pose2 q_true(3.0, 0.0, 0.0);  // moved 3 m along the canal
  std::vector<Eigen::Vector2d> seen_from_current;
  for (const auto& p : canal_seen_from(q_true.x())) {
    seen_from_current.push_back(q_true.inverse().transform(p));
  }
  GaussianPose2 guess;
  guess.mean = q_true;
  guess.cov = Eigen::Vector3d(0.6 * 0.6, 0.6 * 0.6, 0.03 * 0.03).asDiagonal();
  ScanMatchConfig config;
  config.reciprocal_association = reciprocal;
  std::mt19937 rng(testing::seed(21));
  const int trials = 20;
  double sum_m = 0.0;
  for (int t = 0; t < trials; ++t) {
    const ScanMatchResult r = match_scans(noisy(canal_seen_from(0.0), 0.05, rng),
                                          noisy(seen_from_current, 0.05, rng), guess, config);
    EXPECT_TRUE(r.valid) << "trial " << t;
    sum_m += r.estimate.mean.x() - q_true.x();
  }
  return sum_m / trials;
}

TEST(ScanMatching, ReciprocalAssociationRemovesTheShortMotionBiasInACanal) {
  // The current scan sees up to 3 m past the reference's last points ahead; paired one way, those
  // points all fall on the reference's last points and pull the match back.
  const double one_way_m = mean_along_canal_error_m(false);
  const double reciprocal_m = mean_along_canal_error_m(true);
  std::cout << "mean error along the canal: one-way " << one_way_m << " m, reciprocal "
            << reciprocal_m << " m\n";
  // Over 20 seed offsets (stride 1000): one-way -0.58 m (sd 0.059 m), reciprocal -0.0009 m (sd
  // 0.0019 m). The bounds sit 4.7 and 4.8 standard deviations away (under 0.001 % each); a
  // reciprocal bias of 0.013 m fails nine times in ten.
  EXPECT_LT(one_way_m, -0.3);
  EXPECT_LT(std::abs(reciprocal_m), 0.01);
}

TEST(ScanMatching, CrossCovarianceOfTwoMatchesSharingTheCurrentScanMatchesMonteCarlo) {
  // One current scan matched against two references taken from elsewhere. The current points
  // carry their own noise and, per half of the scan, a shared pose error (the dead reckoning
  // while the head turns); the references have independent noise. The two estimates' errors
  // are then correlated through the current scan, as shared_current_covariance predicts.
  const Pose2 pose_a(0.0, 0.0, 0.0), pose_b(2.0, -1.5, 0.06), pose_current(1.0, 0.5, 0.03);
  const double sigma_m = 0.05;
  const Eigen::Vector3d half_sigma(0.08, 0.08, 0.006);  // the halves' shared pose error
  const std::vector<Eigen::Vector2d> world = corner_walls();
  std::vector<ScanPoint> current_true;
  for (std::size_t j = 0; j < world.size(); ++j) {
    ScanPoint p;
    p.p_m = pose_current.inverse().transform(world[j]);
    p.side = j < world.size() / 2 ? 0 : 1;
    // d(delta (+) p) / d(delta) at delta = 0, times the half's standard deviations.
    Matrix23d J;
    J << 1.0, 0.0, -p.p_m.y(), 0.0, 1.0, p.p_m.x();
    p.distortion = J * half_sigma.asDiagonal();
    p.cov_reading = sigma_m * sigma_m * Eigen::Matrix2d::Identity();
    p.cov = p.cov_reading + p.distortion * p.distortion.transpose();
    current_true.push_back(p);
  }
  std::vector<Eigen::Vector2d> world_in_b;
  for (const auto& p : world) world_in_b.push_back(pose_b.inverse().transform(p));
  const Pose2 truth_a = pose_a.between(pose_current), truth_b = pose_b.between(pose_current);
  GaussianPose2 guess_a{truth_a, Eigen::Vector3d(0.04, 0.04, 4e-4).asDiagonal()};
  GaussianPose2 guess_b{truth_b, guess_a.cov};

  std::mt19937 rng(testing::seed(11));
  std::normal_distribution<double> n01(0.0, 1.0);
  const int trials = 1000;
  Eigen::Matrix<double, 6, 6> second_moment = Eigen::Matrix<double, 6, 6>::Zero();
  Eigen::Matrix<double, 6, 1> mean = Eigen::Matrix<double, 6, 1>::Zero();
  Eigen::Matrix3d predicted = Eigen::Matrix3d::Zero(), own_a = Eigen::Matrix3d::Zero(),
                  own_b = Eigen::Matrix3d::Zero();
  for (int t = 0; t < trials; ++t) {
    const Eigen::Vector3d xi[2] = {{n01(rng), n01(rng), n01(rng)}, {n01(rng), n01(rng), n01(rng)}};
    std::vector<ScanPoint> current = current_true;
    for (ScanPoint& p : current) {
      p.p_m += sigma_m * draws_last_first<2>([&] { return n01(rng); }) + p.distortion * xi[p.side];
    }
    const ScanMatchResult a = match_scans(noisy(world, sigma_m, rng), current, guess_a, {});
    const ScanMatchResult b = match_scans(noisy(world_in_b, sigma_m, rng), current, guess_b, {});
    ASSERT_TRUE(a.valid && b.valid);
    Eigen::Matrix<double, 6, 1> e;
    e << pose_difference(a.estimate.mean, truth_a), pose_difference(b.estimate.mean, truth_b);
    mean += e / trials;
    second_moment += e * e.transpose() / trials;
    predicted += shared_current_covariance(a, b, current) / trials;
    own_a += a.estimate.cov / trials;
    own_b += b.estimate.cov / trials;
  }
  const Eigen::Matrix<double, 6, 6> cov = second_moment - mean * mean.transpose();
  const Eigen::Matrix3d empirical = cov.topRightCorner<3, 3>();
  // The statistic: correlations, the model's (its cross term over its own standard deviations)
  // against the sample's. Their spread over 41 seed offsets at 1,000 trials: 0.003, 0.002 and
  // 0.010 on the same axis (x, y, yaw: yaw's is twice the normal-theory (1 - rho^2)/sqrt(n),
  // its errors being heavy-tailed), about 0.03 across axes (rho near 0). The model's own error,
  // measured as the mean over those offsets: same axis at most 0.03 (yaw: model 0.978, sample
  // 0.948); across axes up to 0.13 (y with yaw: model -0.145, sample -0.03 to +0.01;
  // point-to-point pairs on walls sampled every 0.5 m slide together, which the model's
  // independent sampling error does not say). Bounds: that model error plus 3.3 spreads
  // (two-sided 0.001 per entry): 0.065 on the same axis, 0.25 across. Caught: a cross term
  // scaled by 0.9 or less (same-axis model correlations 0.88-0.89 against 0.95-0.98). Before,
  // 400 trials and the model's cross term divided by the sample's standard deviations, which
  // the spIC covariance understates by up to a fifth in x (0.0042 against 0.0050): that mixed
  // the match's own covariance error into the cross term, and a 0.1 bound failed in 15 of 20
  // seed offsets.
  const Eigen::Vector3d sd_a = cov.diagonal().head<3>().cwiseSqrt();
  const Eigen::Vector3d sd_b = cov.diagonal().tail<3>().cwiseSqrt();
  const Eigen::Matrix3d scale = sd_a * sd_b.transpose();
  const Eigen::Matrix3d rho_predicted = predicted.cwiseQuotient(
      own_a.diagonal().cwiseSqrt() * own_b.diagonal().cwiseSqrt().transpose());
  const Eigen::Matrix3d rho_empirical = empirical.cwiseQuotient(scale);
  std::cout << "cross-correlation predicted\n"
            << rho_predicted << "\nempirical\n"
            << rho_empirical << "\nmatch a's own covariance, spIC\n"
            << own_a << "\nempirical\n"
            << cov.topLeftCorner<3, 3>() << "\n";
  // The shared error dominates here: the sample's same-axis correlations 0.95-0.98, their sd over
  // seed offsets up to 0.010 (above), so 0.8 lies over 14 of them below.
  EXPECT_GT(rho_empirical.diagonal().minCoeff(), 0.8);
  // The bounds above: the model's error plus 3.3 spreads, two-sided 0.001 per entry.
  EXPECT_LT((rho_predicted - rho_empirical).diagonal().cwiseAbs().maxCoeff(), 0.065);
  EXPECT_LT((rho_predicted - rho_empirical).cwiseAbs().maxCoeff(), 0.25);
}

}  // namespace
}  // namespace msislab
