// World-centric trajectory SLAM on a synthetic loop: a vehicle drives twice around a walled basin,
// its odometry drifts, and matching scans against earlier ones pulls the trajectory back; empty
// scans are skipped without harm.
#include "slam/worldcentric_slam.hpp"

#include <gtest/gtest.h>

#include <Eigen/LU>
#include <random>

namespace msislab {
namespace {

/// Walls of a 40 x 30 m basin plus a pier and a block inside, sampled every 0.4 m.
std::vector<Eigen::Vector2d> basin() {
  std::vector<Eigen::Vector2d> points;
  auto wall = [&](Eigen::Vector2d a, Eigen::Vector2d b) {
    const int n = static_cast<int>((b - a).norm() / 0.4);
    for (int i = 0; i <= n; ++i) points.push_back(a + (b - a) * i / n);
  };
  wall({-20, -15}, {20, -15});
  wall({20, -15}, {20, 15});
  wall({20, 15}, {-20, 15});
  wall({-20, 15}, {-20, -15});
  wall({0, 15}, {0, 8});     // a pier
  wall({-6, -4}, {-2, -4});  // a block
  wall({-2, -4}, {-2, -1});
  return points;
}

struct Loop {
  std::vector<Pose2> truth;  ///< scan poses in the world
  std::vector<Scan> scans;
};

/// Scan poses every 4 m around a 24 x 16 m rectangle, twice; each scan sees the basin within
/// 25 m (point noise 0.05 m); motions are the true ones with noise (0.08 m, 0.08 m, 0.6 deg).
Loop make_loop(unsigned seed, bool empty_scans) {
  std::mt19937 rng(seed);
  std::normal_distribution<double> n01(0.0, 1.0);
  const auto world = basin();
  std::vector<Pose2> truth;
  for (int lap = 0; lap < 2; ++lap) {
    for (int i = 0; i < 6; ++i) truth.emplace_back(-12.0 + 4 * i, -8.0, 0.0);
    for (int i = 0; i < 4; ++i) truth.emplace_back(12.0, -8.0 + 4 * i, M_PI / 2);
    for (int i = 0; i < 6; ++i) truth.emplace_back(12.0 - 4 * i, 8.0, M_PI);
    for (int i = 0; i < 4; ++i) truth.emplace_back(-12.0, 8.0 - 4 * i, -M_PI / 2);
  }
  const Eigen::Vector3d sigma(0.08, 0.08, 0.6 * M_PI / 180);
  Loop loop;
  loop.truth = truth;
  for (std::size_t k = 0; k < truth.size(); ++k) {
    Scan scan;
    scan.t_s = static_cast<double>(k);
    const Pose2 true_motion = k == 0 ? truth[0] : truth[k - 1].between(truth[k]);
    const Eigen::Vector3d noise(sigma.x() * n01(rng), sigma.y() * n01(rng), sigma.z() * n01(rng));
    scan.motion.mean = k == 0 ? true_motion : Pose2(true_motion.vector() + noise);
    scan.motion.cov = k == 0 ? Eigen::Matrix3d::Identity() * 1e-9
                             : Eigen::Matrix3d(sigma.cwiseProduct(sigma).asDiagonal());
    const bool blind = empty_scans && k % 7 == 3;
    for (const auto& p_world : world) {
      const Eigen::Vector2d p = truth[k].inverse().transform(p_world);
      if (blind || p.norm() > 25.0) continue;
      ScanPoint point;
      point.p_m = p + 0.05 * Eigen::Vector2d(n01(rng), n01(rng));
      point.cov = 0.05 * 0.05 * Eigen::Matrix2d::Identity();
      point.p_vehicle_m = point.p_m;
      scan.points.push_back(point);
    }
    loop.scans.push_back(scan);
  }
  return loop;
}

double final_error_m(const std::vector<Pose2>& estimate, const std::vector<Pose2>& truth) {
  return (estimate.back().translation() - truth.back().translation()).norm();
}

TEST(WorldCentricSlam, ClosesTheLoopBetterThanOdometry) {
  int better = 0;
  double nees_sum = 0.0;
  for (unsigned seed = 1; seed <= 5; ++seed) {
    const Loop loop = make_loop(seed, false);
    WorldCentricSlam slam(TrajectorySlamConfig{}, GaussianPose2{});
    std::vector<Pose2> odometry;
    Pose2 chained;
    int accepted = 0;
    for (const Scan& scan : loop.scans) {
      accepted += slam.add_scan(scan).accepted;
      chained = chained.compose(scan.motion.mean);
      odometry.push_back(chained);
    }
    std::vector<Pose2> estimate;
    for (std::size_t i = 0; i < slam.scans(); ++i) estimate.push_back(slam.scan_pose_world(i).mean);
    const double slam_m = final_error_m(estimate, loop.truth);
    const double odometry_m = final_error_m(odometry, loop.truth);
    std::cout << "seed " << seed << ": final error SLAM " << slam_m << " m, odometry " << odometry_m
              << " m, " << accepted << " matches accepted\n";
    EXPECT_GT(accepted, static_cast<int>(loop.scans.size()));
    EXPECT_LT(slam_m, 0.3);
    better += slam_m < odometry_m;
    const GaussianPose2 last = slam.scan_pose_world(slam.scans() - 1);
    const Eigen::Vector3d e = pose_difference(last.mean, loop.truth.back());
    nees_sum += e.dot(last.cov.inverse() * e);
  }
  EXPECT_GE(better, 4);
  // The final pose's covariance covers its error: the NEES averaged over the 5 runs stays under
  // the two-sided 99% upper bound for 5 runs.
  const double anees = nees_sum / 5.0;
  std::cout << "final-pose NEES averaged over 5 runs: " << anees << " (99% upper bound "
            << average_chi2_bounds(5, 3, 0.01).second << ")\n";
  EXPECT_LT(anees, average_chi2_bounds(5, 3, 0.01).second);
}

TEST(WorldCentricSlam, EmptyScansAreSkippedWithoutHarm) {
  const Loop loop = make_loop(3, true);
  WorldCentricSlam slam(TrajectorySlamConfig{}, GaussianPose2{});
  int skipped = 0;
  for (const Scan& scan : loop.scans) {
    const SlamStepStats stats = slam.add_scan(scan);
    if (scan.points.empty()) {
      EXPECT_EQ(stats.matched, 0);
      ++skipped;
    }
  }
  EXPECT_GT(skipped, 3);
  EXPECT_EQ(slam.scans(), loop.scans.size());
  EXPECT_LT(final_error_m({slam.scan_pose_world(slam.scans() - 1).mean}, loop.truth), 0.5);
}

TEST(WorldCentricSlam, RelativePoseJacobianMatchesTheChain) {
  const Loop loop = make_loop(2, false);
  WorldCentricSlam slam(TrajectorySlamConfig{}, GaussianPose2{});
  for (std::size_t k = 0; k < 6; ++k) slam.add_scan(loop.scans[k]);
  Eigen::MatrixXd H;
  const Pose2 h = slam.relative_pose(1, 5, &H);
  ASSERT_EQ(H.cols(), 18);
  // Columns outside x_2..x_5 are zero; inside, they match finite differences of h.
  EXPECT_EQ(H.leftCols(6).norm(), 0.0);
  const double step = 1e-6;
  for (int c = 6; c < 18; ++c) {
    std::vector<Pose2> plus = slam.motions(), minus = slam.motions();
    Eigen::Vector3d d = Eigen::Vector3d::Zero();
    d(c % 3) = step;
    plus[static_cast<std::size_t>(c / 3)] =
        Pose2(plus[static_cast<std::size_t>(c / 3)].vector() + d);
    minus[static_cast<std::size_t>(c / 3)] =
        Pose2(minus[static_cast<std::size_t>(c / 3)].vector() - d);
    Pose2 hp, hm;
    for (std::size_t j = 2; j <= 5; ++j) hp = hp.compose(plus[j]), hm = hm.compose(minus[j]);
    const Eigen::Vector3d numeric = pose_difference(hp, hm) / (2 * step);
    EXPECT_LT((H.col(c) - numeric).norm(), 1e-6) << "column " << c;
  }
  EXPECT_LT(pose_difference(h, compose(compose(GaussianPose2{slam.motions()[2], {}},
                                               GaussianPose2{slam.motions()[3], {}}),
                                       compose(GaussianPose2{slam.motions()[4], {}},
                                               GaussianPose2{slam.motions()[5], {}}))
                                   .mean)
                .norm(),
            1e-12);
}

}  // namespace
}  // namespace msislab
