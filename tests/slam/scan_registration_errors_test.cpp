// Scan registration errors (docs/trajectory_slam.md, "Scan registration errors"): spIC's
// covariance split by whose error it is; the scans' shared errors as states (each half-scan's
// motion error, each scan's rigid error for its points); the observation's Jacobian with those
// states against central differences in both filters; and the synthetic loop's final pose
// consistent with them where, without them, scans reused across steps make the filters
// overconfident.
#include <gtest/gtest.h>

#include <Eigen/Eigenvalues>
#include <array>
#include <cmath>
#include <iostream>
#include <memory>
#include <random>

#include "slam/robocentric_slam.hpp"
#include "slam/scan_matching.hpp"
#include "slam/worldcentric_slam.hpp"
#include "stats/chi_square.hpp"
#include "test_support.hpp"
#include "tests/draws.hpp"
#include "tests/slam/observation_jacobian_check.hpp"
#include "tests/slam/synthetic_loop.hpp"

namespace msislab {
namespace {

double smallest_eigenvalue(const Eigen::Matrix3d& A) {
  return Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d>(A).eigenvalues().minCoeff();
}

TrajectorySlamConfig with_scan_errors() {
  TrajectorySlamConfig config;
  config.filter.scan_shared_errors = ScanSharedErrors::kMotionAndPoints;
  return config;
}

/// The loop's scans as a scanning sonar's: each point displaced by its half-scan's motion error
/// D xi_side (side 0: the beams before the centre, here the points behind the vehicle), D growing
/// with the point's angle from the centre as a half-revolution's dead-reckoning error does; the
/// points' covariance holds D D^T beside their reading noise.
Loop distorted(Loop loop) {
  for (Scan& scan : loop.scans) {
    for (ScanPoint& p : scan.points) {
      const double angle_rad = std::atan2(p.p_m.y(), p.p_m.x());
      p.side = angle_rad < 0.0 ? 0 : 1;
      const double f = std::abs(angle_rad) / M_PI;  // 0 at the centre beam, 1 at the ends
      Matrix23d J_pose;                             // d(point)/d(pose): [I, perp(p)]
      J_pose << 1.0, 0.0, -p.p_m.y(), 0.0, 1.0, p.p_m.x();
      p.distortion = f * J_pose * Eigen::Vector3d(0.03, 0.03, 0.3 * M_PI / 180).asDiagonal();
      p.cov = p.cov_reading + p.distortion * p.distortion.transpose();
    }
  }
  return loop;
}

// Each scan's share and the pairs' own part are covariances (not a statistic: sums of
// J C J^T); the current scan's share is what its loadings give (shared_current_covariance of a
// match with itself, the half-scans' terms among them), each half-scan's loadings M M^T lie
// within its scan's share, and with shared point errors off the parts still sum within the whole.
TEST(ScanRegistrationErrors, SpicSplitsItsCovarianceByWhoseErrorItIs) {
  const Loop plain = make_loop(4, false);
  for (const bool halves : {false, true}) {
    const Loop loop = halves ? distorted(plain) : plain;
    for (const bool shared : {true, false}) {
      ScanMatchConfig config;
      config.shared_point_errors = shared;
      GaussianPose2 guess{loop.truth[4].between(loop.truth[6]), loop.scans[5].motion.cov * 2.0};
      const ScanMatchResult m =
          match_scans(loop.scans[4].points, loop.scans[6].points, guess, config);
      ASSERT_TRUE(m.valid);
      const double scale = m.estimate.cov.norm();
      EXPECT_GT(smallest_eigenvalue(m.current_share), 0.0);
      EXPECT_GT(smallest_eigenvalue(m.reference_share), 0.0);
      const Eigen::Matrix3d own = m.estimate.cov - m.current_share - m.reference_share;
      EXPECT_GT(smallest_eigenvalue(own), -1e-12 * scale) << "shared " << shared;
      // Each scan carries 38 % of the match's variance on the plain loop (0.05 m points on
      // both), the surfaces' sampling every 0.4 m the other 23 %: the bound is half of that (not
      // a statistic: one fixed pair of scans).
      EXPECT_GT(m.current_share.trace(), 0.2 * m.estimate.cov.trace());
      EXPECT_GT(m.reference_share.trace(), 0.2 * m.estimate.cov.trace());
      if (!shared) continue;
      const Eigen::Matrix3d from_loadings = shared_current_covariance(m, m, loop.scans[6].points);
      EXPECT_LT((from_loadings - m.current_share).norm(), 1e-9 * scale);
      Eigen::Matrix3d points_k = m.current_share, points_j = m.reference_share;
      for (std::size_t side = 0; side < 2; ++side) {
        points_k -= m.current_loading.half[side] * m.current_loading.half[side].transpose();
        points_j -= m.reference_half[side] * m.reference_half[side].transpose();
      }
      EXPECT_GT(smallest_eigenvalue(points_k), -1e-12 * scale);
      EXPECT_GT(smallest_eigenvalue(points_j), -1e-12 * scale);
      // The distorted scans' halves carry part of each share; the plain ones' none.
      EXPECT_EQ(halves, m.current_loading.half[0].norm() > 0.0);
      EXPECT_EQ(halves, m.reference_half[1].norm() > 0.0);
    }
  }
}

/// distorted(loop) with the distortion drawn: each half-scan's points moved by D xi_side, xi_side
/// ~ N(0, I) drawn once per half-scan (independent of the motions' noise, where a real scan's is
/// the same dead reckoning's error).
Loop with_drawn_distortion(Loop loop, unsigned seed) {
  loop = distorted(loop);
  std::mt19937 rng(seed + 7000);
  std::normal_distribution<double> n01(0.0, 1.0);
  for (Scan& scan : loop.scans) {
    std::array<Eigen::Vector3d, 2> xi;
    for (Eigen::Vector3d& x : xi) x = draws_last_first<3>([&] { return n01(rng); });
    for (ScanPoint& p : scan.points) {
      p.p_m += p.distortion * xi[static_cast<std::size_t>(p.side)];
      p.p_vehicle_m = p.p_m;
    }
  }
  return loop;
}

/// Checks H of the stacked residual of one observation of scan b against scan a, with its
/// shared errors, against central differences over the calibration's columns (where the scans'
/// errors live).
template <class Filter>
void expect_shared_error_jacobian(Filter& slam, const RelativePoseObservation& o, std::size_t b) {
  Eigen::MatrixXd H;
  slam.stacked_residual(slam.state(), b, {o}, &H);
  const double step = 1e-6;
  for (Eigen::Index i = 0; i < slam.parameters().size(); ++i) {
    slam.parameters()(i) += step;
    const Eigen::VectorXd plus = slam.stacked_residual(slam.state(), b, {o}, nullptr);
    slam.parameters()(i) -= 2 * step;
    const Eigen::VectorXd minus = slam.stacked_residual(slam.state(), b, {o}, nullptr);
    slam.parameters()(i) += step;
    // The residual is z - h: its Jacobian is -dh.
    EXPECT_LT((H.col(i) + (plus - minus) / (2 * step)).norm(), 1e-6) << "parameter " << i;
  }
}

// h = (-)e_a (+) h(X) (+) e_b + sum M xi with the range scale and the clock offset before it:
// every column (the calibration, both scans' rigid errors and half-scan errors, the elements)
// against central differences, in both filters, and in the robocentric one during a step (its
// newest element raw).
TEST(ScanRegistrationErrors, ObservationJacobians) {
  const Loop loop = distorted(scaled(clock_offset_loop(2, 0.1), 0.97));
  TrajectorySlamConfig config = with_scan_errors();
  config.calibration.range_scale = true;
  config.calibration.clock_offset = true;
  Open<WorldCentricSlam> world(config, GaussianPose2{});
  Open<RoboCentricSlam> robot(config, GaussianPose2{});
  for (std::size_t k = 0; k < 8; ++k) world.add_scan(loop.scans[k]), robot.add_scan(loop.scans[k]);
  // Two calibration parameters, then each of the 8 scans' rigid error and its two half-scans'
  // errors, each in the state since its first match; the matches have moved them off zero.
  ASSERT_EQ(world.parameters().size(), 2 + 9 * 8);
  ASSERT_EQ(robot.parameters().size(), 2 + 9 * 8);
  EXPECT_GT(world.parameters().tail(9 * 8).cwiseAbs().maxCoeff(), 1e-4);
  expect_observation_jacobian(world, 1, 5);
  expect_observation_jacobian(world, 6, 7);
  expect_observation_jacobian(robot, 0, 7);
  expect_observation_jacobian(robot, 2, 4);
  // A match's loadings on half-scan errors in the state (rows 2.. hold the scans' errors).
  RelativePoseObservation o;
  o.reference = 3;
  o.z = world.observed_relative_pose(3, 6, nullptr);
  o.shared = {{2, Eigen::Matrix3d::Identity() * 0.3}, {11, Eigen::Matrix3d::Random()}};
  expect_shared_error_jacobian(world, o, 6);
  expect_shared_error_jacobian(robot, o, 6);
  robot.velocities().push_back(loop.scans[8].velocity_vehicle);  // as add_scan does first
  robot.predict(loop.scans[8].motion);
  expect_observation_jacobian(robot, 1, 8);
  expect_observation_jacobian(robot, 7, 8);
}

// The synthetic loop's final pose with the scans' errors in the state, in both filters: its NEES
// averaged over 5 loops under the 99.9 % bound for 5 runs (two-sided, an upper tail of 0.05 %).
// Measured over 100 seed offsets (500 loops a filter): the average's median is 2.82 (2.87 for a
// consistent filter: the chi-square's with 15 DOF over 5), and it passes this bound in 99 of 100
// offsets per filter, the 99 % bound in 96. Without the states, the same loops' median is 4.74
// and 13 of 100 pass the 99 % bound (BothMethods.ClosesTheLoopBetterThanOdometry, whose
// bound is the 99 % one). So this test fails about 1 % of streams, above its bound's 0.05 %: the
// innovation gate's lock (docs/reliability.md), where a correct match in the gate's tail is
// rejected and nothing brings the state back, is still the cause.
TEST(ScanRegistrationErrors, TheSyntheticLoopsFinalPoseIsConsistent) {
  for (const bool robocentric : {true, false}) {
    double nees_sum = 0.0;
    for (unsigned seed = 1; seed <= 5; ++seed) {
      const Loop loop = make_loop(testing::seed(seed), false);
      std::unique_ptr<TrajectorySlam> slam;
      if (robocentric) {
        slam = std::make_unique<RoboCentricSlam>(with_scan_errors(), GaussianPose2{});
      } else {
        slam = std::make_unique<WorldCentricSlam>(with_scan_errors(), GaussianPose2{});
      }
      for (const Scan& scan : loop.scans) slam->add_scan(scan);
      const GaussianPose2 last = slam->scan_pose_world(loop.scans.size() - 1);
      const Eigen::Vector3d e = pose_difference(last.mean, loop.truth.back());
      nees_sum += e.dot(last.cov.inverse() * e);
    }
    const double anees = nees_sum / 5.0;
    std::cout << (robocentric ? "robocentric" : "world-centric")
              << ": final-pose NEES averaged over 5 loops " << anees << "\n";
    EXPECT_LT(anees, average_chi2_bounds(5, 3, 0.001).second);
  }
}

// A chain of consecutive matches (one match per scan) over scans whose halves carry their own
// motion errors: without the half-scan errors in the state each scan's error enters two matches
// with opposite signs and the chain is underconfident; with them (`motion`), consistent. The
// statistic: every scan pose's NEES (3 DOF) averaged over the 5 loops' 195 steps, which are
// correlated along each loop, so its spread is measured, not derived. Over 40 seed offsets
// (k x 1000): with `motion` mean 2.93, sd 0.68 (1.60-4.97); without, median 1.56 (0.89-3.03); the
// difference with minus without mean 1.27, sd 0.45, above zero in 40 of 40. The bounds: `motion`
// within 3 +- 3.3 sd (0.1 % two-sided) and above `none` (2.8 sd from its mean, 0.25 %); together
// about 0.35 % of correct streams fail. They catch a state that leaves the chain as
// underconfident as without it, or one overconfident by 75 %.
TEST(ScanRegistrationErrors, HalfScanErrorsMakeAChainOfMatchesConsistent) {
  std::array<double, 2> anees{};
  for (const ScanSharedErrors held : {ScanSharedErrors::kNone, ScanSharedErrors::kMotion}) {
    double nees_sum = 0.0;
    int steps = 0;
    for (unsigned seed = 1; seed <= 5; ++seed) {
      const Loop loop =
          with_drawn_distortion(make_loop(testing::seed(seed), false), testing::seed(seed));
      TrajectorySlamConfig config;
      config.filter.scan_shared_errors = held;
      config.front_end.max_matches_per_scan = 1;
      RoboCentricSlam slam(config, GaussianPose2{});
      for (std::size_t k = 0; k < loop.scans.size(); ++k) {
        slam.add_scan(loop.scans[k]);
        if (k == 0) continue;
        const GaussianPose2 pose = slam.scan_pose_world(k);
        const Eigen::Vector3d e = pose_difference(pose.mean, loop.truth[k]);
        nees_sum += e.dot(pose.cov.inverse() * e);
        ++steps;
      }
    }
    anees[held == ScanSharedErrors::kMotion] = nees_sum / steps;
  }
  std::cout << "every scan pose's NEES averaged: without the half-scan errors " << anees[0]
            << ", with them " << anees[1] << "\n";
  EXPECT_GT(anees[1], 3.0 - 3.3 * 0.68);
  EXPECT_LT(anees[1], 3.0 + 3.3 * 0.68);
  EXPECT_GT(anees[1], anees[0]);
}

// Off, the state holds no scan's error (the default filters are unchanged).
TEST(ScanRegistrationErrors, OffTheStateHoldsNone) {
  const Loop loop = make_loop(2, false);
  Open<RoboCentricSlam> robot(TrajectorySlamConfig{}, GaussianPose2{});
  for (std::size_t k = 0; k < 8; ++k) robot.add_scan(loop.scans[k]);
  EXPECT_EQ(robot.parameters().size(), 0);
}

}  // namespace
}  // namespace msislab
