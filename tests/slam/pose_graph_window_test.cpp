// The pose graph's online window (online_window_scans): the joint covariance of the newest nodes
// kept from scan to scan instead of factoring the whole graph each scan. In the linear limit
// (noise 1e-4 of the usual, so that no solve moves a linearisation point) it must give what the
// whole graph gives wherever it claims to: with every node in the window, and with nodes dropped
// while every candidate lies in the window. An older candidate within online_old_chain_scans of
// the belief joins correlated with it, and stays in it for the next matches: the online
// covariance is then never below the whole graph's (no information counted twice). Farther ones
// are its one approximation: counted, and the smoothing solve still frees the whole graph.
#include <gtest/gtest.h>

#include <Eigen/Cholesky>
#include <Eigen/Eigenvalues>
#include <set>

#include "slam/pose_graph_slam.hpp"
#include "tests/slam/synthetic_loop.hpp"

namespace msislab {
namespace {

struct Online {
  std::vector<GaussianPose2> online, smoothed;
  int outside = 0, accepted = 0, uncorrelated = 0;
  /// Accepted matches of a node older than the window by the scan after one that matched it too.
  int old_matched_again = 0;
};

Online run_window(const std::vector<Scan>& scans, int window, const TrajectorySlamConfig& front) {
  PoseGraphSlamConfig config;
  config.online_window_scans = window;
  PoseGraphSlam slam(front.front_end, front.calibration, config, GaussianPose2{});
  Online out;
  std::set<std::size_t> old_before;  // old references the previous scan accepted
  for (const Scan& scan : scans) {
    std::set<std::size_t> old_now;
    for (const MatchRecord& m : slam.add_scan(scan).matches) {
      if (window <= 0 || m.rejection != MatchRejection::kNone) continue;
      if (m.scan < m.reference + static_cast<std::size_t>(window)) continue;
      old_now.insert(m.reference);
      out.old_matched_again += static_cast<int>(old_before.count(m.reference));
    }
    old_before = old_now;
  }
  out.online = *slam.online_poses();
  slam.finish();
  for (std::size_t i = 0; i < slam.scans(); ++i) out.smoothed.push_back(slam.scan_pose_world(i));
  out.outside = slam.matches_outside_window();
  out.uncorrelated = slam.old_nodes_uncorrelated();
  out.accepted = slam.totals().accepted;
  return out;
}

/// The covariances within cov_relative of the whole graph's (relative, Frobenius), the means within
/// mean_m: the solves stop at Ceres' tolerances from different warm starts, a few 1e-7 m apart
/// where the loop's noise is 8e-6 m.
void expect_same(const std::vector<GaussianPose2>& whole, const std::vector<GaussianPose2>& window,
                 double cov_relative, double mean_m) {
  ASSERT_EQ(whole.size(), window.size());
  for (std::size_t k = 0; k < whole.size(); ++k) {
    EXPECT_LT((window[k].cov - whole[k].cov).norm(), cov_relative * whole[k].cov.norm()) << k;
    EXPECT_LT(pose_difference(window[k].mean, whole[k].mean).norm(), mean_m) << k;
  }
}

TEST(PoseGraphWindow, HoldingEveryNodeItGivesTheWholeGraphsBelief) {
  const Loop loop = make_loop(5, false, 1e-4);
  const Online whole = run_window(loop.scans, 0, {});
  const Online window = run_window(loop.scans, 1000, {});
  EXPECT_GT(whole.accepted, static_cast<int>(loop.scans.size()));
  EXPECT_EQ(window.accepted, whole.accepted);
  EXPECT_EQ(window.outside, 0);
  expect_same(whole.online, window.online, 1e-6, 1e-6);
  expect_same(whole.smoothed, window.smoothed, 1e-6, 1e-6);
}

TEST(PoseGraphWindow, DroppingNodesIsExactWhileTheCandidatesAreInIt) {
  // Most of a lap, short of closing: candidates within 9 m are at most 2 scans back, so a window of
  // 5 nodes holds them all while older nodes are dropped scan after scan.
  const Loop loop = make_loop(5, false, 1e-4);
  const std::vector<Scan> lap(loop.scans.begin(), loop.scans.begin() + 18);
  TrajectorySlamConfig front;
  front.front_end.association_distance_m = 9.0;
  const Online whole = run_window(lap, 0, front);
  const Online window = run_window(lap, 5, front);
  EXPECT_GT(whole.accepted, 18);  // not a statistic (noise 1e-4): 38, the lap's structure
  EXPECT_EQ(window.accepted, whole.accepted);
  EXPECT_EQ(window.outside, 0);
  expect_same(whole.online, window.online, 1e-6, 1e-6);
}

TEST(PoseGraphWindow, OlderCandidatesAreCountedAndTheSmoothingSolvesEverything) {
  // Two laps at the usual noise with a window of 5: the second lap's loop closures reach 20 scans
  // back, to nodes the online solves hold. The online covariances stay positive definite and the
  // loop still closes.
  const Loop loop = make_loop(1, false);
  const Online window = run_window(loop.scans, 5, {});
  // Not a statistic: the second lap's candidates lie 20 scans back, beyond the window (46 here).
  EXPECT_GT(window.outside, 10);
  EXPECT_GT(window.accepted, static_cast<int>(loop.scans.size()));
  for (const GaussianPose2& p : window.online) {
    EXPECT_EQ(Eigen::LLT<Eigen::Matrix3d>(p.cov).info(), Eigen::Success);
  }
  Pose2 dead_reckoning;
  for (const Scan& scan : loop.scans) dead_reckoning = dead_reckoning + scan.motion.mean;
  const auto error_m = [&](const Pose2& p, std::size_t k) {
    return (p.translation() - loop.truth[k].translation()).norm();
  };
  const std::size_t last = loop.truth.size() - 1;
  EXPECT_LT(error_m(window.smoothed.back().mean, last), 0.5 * error_m(dead_reckoning, last));
}

TEST(PoseGraphWindow, OldNodesMatchedAgainAreNotCountedTwice) {
  // The two laps in the linear limit with a window of 10: the second lap's candidates lie 20 scans
  // back, 10 beyond the window, each matched by several successive scans. Each joins as its
  // neighbour in the belief composed with the odometry between them, then stays in the belief, so
  // no prior enters twice: the online covariance is nowhere below the whole graph's (every
  // generalised eigenvalue of the pair at least 1) and, the chain dropping only the first lap's
  // short matches, close above it. Re-adding each old node's marginal as independent information
  // on every match put it at half the whole graph's.
  const Loop loop = make_loop(5, false, 1e-4);
  const Online whole = run_window(loop.scans, 0, {});
  const Online window = run_window(loop.scans, 10, {});
  // Not statistics (noise 1e-4): the loop's structure, 49 and 29.
  EXPECT_GT(window.outside, 20);            // not a statistic
  EXPECT_GT(window.old_matched_again, 10);  // not a statistic
  EXPECT_EQ(window.uncorrelated, 0);
  ASSERT_EQ(window.online.size(), whole.online.size());
  for (std::size_t k = 0; k < whole.online.size(); ++k) {
    const Eigen::GeneralizedSelfAdjointEigenSolver<Eigen::Matrix3d> ratio(window.online[k].cov,
                                                                          whole.online[k].cov);
    EXPECT_GT(ratio.eigenvalues().minCoeff(), 1.0 - 1e-6) << k;
    // Not a statistic (the linear limit): at most 1.019 here, the first lap's short matches the
    // chain drops; a window that lost the old nodes' information would put it higher.
    EXPECT_LT(ratio.eigenvalues().maxCoeff(), 1.05) << k;
  }
}

}  // namespace
}  // namespace msislab
