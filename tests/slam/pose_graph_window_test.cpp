// The pose graph's online window (online_window_scans): the joint covariance of the newest nodes
// kept from scan to scan instead of factoring the whole graph each scan. In the linear limit
// (noise 1e-4 of the usual, so that no solve moves a linearisation point) it must give what the
// whole graph gives wherever it claims to: with every node in the window, and with nodes dropped
// while every candidate lies in the window. Older candidates are its one approximation: counted,
// and the smoothing solve still frees the whole graph.
#include <gtest/gtest.h>

#include <Eigen/Cholesky>

#include "slam/pose_graph_slam.hpp"
#include "tests/slam/synthetic_loop.hpp"

namespace msislab {
namespace {

struct Online {
  std::vector<GaussianPose2> online, smoothed;
  int outside = 0, accepted = 0;
};

Online run_window(const std::vector<Scan>& scans, int window, const TrajectorySlamConfig& front) {
  PoseGraphSlamConfig config;
  config.online_window_scans = window;
  PoseGraphSlam slam(front, config, GaussianPose2{});
  for (const Scan& scan : scans) slam.add_scan(scan);
  Online out;
  out.online = *slam.online_poses();
  for (std::size_t i = 0; i < slam.scans(); ++i) out.smoothed.push_back(slam.scan_pose_world(i));
  out.outside = slam.matches_outside_window();
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
  front.association_distance_m = 9.0;
  const Online whole = run_window(lap, 0, front);
  const Online window = run_window(lap, 5, front);
  EXPECT_GT(whole.accepted, 18);
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

}  // namespace
}  // namespace msislab
