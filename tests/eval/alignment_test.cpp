// SE(2) alignment: the closed form recovers a random rigid motion exactly and is the least-squares
// minimum under noise; degenerate input is an error; moving an estimate and its truth by one rigid
// motion leaves the NEES unchanged (the covariance turns with the pose).
#include "eval/alignment.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <stdexcept>
#include <string>
#include "tests/draws.hpp"

namespace msislab {
namespace {

std::vector<Eigen::Vector2d> moved(const Pose2& T, const std::vector<Eigen::Vector2d>& points) {
  std::vector<Eigen::Vector2d> out;
  for (const Eigen::Vector2d& p : points) out.push_back(T.transform(p));
  return out;
}

double cost(const Pose2& T, const std::vector<Eigen::Vector2d>& p,
            const std::vector<Eigen::Vector2d>& q) {
  double sum = 0.0;
  for (std::size_t i = 0; i < p.size(); ++i) sum += (q[i] - T.transform(p[i])).squaredNorm();
  return sum;
}

TEST(Alignment, ClosedFormRecoversRandomRigidMotions) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> coordinate(-100.0, 100.0);
  std::uniform_real_distribution<double> angle(-M_PI, M_PI);
  for (int trial = 0; trial < 50; ++trial) {
    std::vector<Eigen::Vector2d> p;
    for (int i = 0; i < 2 + trial % 20; ++i) {
      p.push_back(draws_last_first<2>([&] { return coordinate(rng); }));
    }
    // The last trials sit at the wrap-around, where yaw = +-pi.
    const double yaw_rad = trial >= 48 ? (trial == 48 ? M_PI : -M_PI + 1e-9) : angle(rng);
    const Eigen::Vector2d t = draws_last_first<2>([&] { return coordinate(rng); });
    const Pose2 T(t.x(), t.y(), yaw_rad);
    const Pose2 fit = align_se2(p, moved(T, p));
    EXPECT_NEAR(fit.x(), T.x(), 1e-9) << trial;
    EXPECT_NEAR(fit.y(), T.y(), 1e-9) << trial;
    EXPECT_NEAR(normalize_angle(fit.yaw() - T.yaw()), 0.0, 1e-12) << trial;
  }
}

TEST(Alignment, IsTheLeastSquaresMinimumUnderNoise) {
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> coordinate(-50.0, 50.0);
  std::normal_distribution<double> noise(0.0, 2.0);
  std::vector<Eigen::Vector2d> p, q;
  const Pose2 T(12.0, -3.0, 0.7);
  for (int i = 0; i < 30; ++i) {
    p.push_back(draws_last_first<2>([&] { return coordinate(rng); }));
    q.push_back(T.transform(p.back()) + draws_last_first<2>([&] { return noise(rng); }));
  }
  const Pose2 fit = align_se2(p, q);
  const double at_fit = cost(fit, p, q);
  for (int k = 0; k < 3; ++k) {
    for (const double step : {-1e-4, 1e-4}) {
      Eigen::Vector3d v = fit.vector();
      v[k] += step;
      EXPECT_GT(cost(Pose2(v), p, q), at_fit) << "direction " << k << " step " << step;
    }
  }
}

// Expects align_se2 to throw std::invalid_argument whose message contains `word`.
void expect_degenerate(const std::vector<Eigen::Vector2d>& p, const std::vector<Eigen::Vector2d>& q,
                       const std::string& word) {
  try {
    align_se2(p, q);
    ADD_FAILURE() << "no error for " << p.size() << " positions";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find(word), std::string::npos) << e.what();
  }
}

TEST(Alignment, DegenerateInputIsAnError) {
  const Eigen::Vector2d a(1.0, 2.0), b(3.0, -1.0);
  expect_degenerate({}, {}, "2 distinct positions");
  expect_degenerate({a}, {b}, "2 distinct positions");
  expect_degenerate({a, a, a}, {a, b, b}, "2 distinct positions");  // one distinct estimate
  expect_degenerate({a, b}, {b, b}, "2 distinct positions");        // one distinct truth
  expect_degenerate({a, b}, {a}, "1 truth positions");
  // Distinct positions whose cross-covariance vanishes: every rotation fits them equally well.
  expect_degenerate({{1, 0}, {-1, 0}, {0, 0}}, {{0, 1}, {0, 1}, {0, -2}}, "undetermined");
  // Two distinct positions are enough.
  const Pose2 T(5.0, 6.0, -2.0);
  const Pose2 fit = align_se2({a, b}, moved(T, {a, b}));
  EXPECT_NEAR((fit.vector() - T.vector()).norm(), 0.0, 1e-12);
}

std::vector<StampedPose> curve(double t0_s, const Pose2& T) {
  std::vector<StampedPose> out;
  for (int k = 0; k <= 100; ++k) {
    const double t_s = 0.5 * k;
    out.push_back({t0_s + t_s, {T + Pose2(t_s, 0.02 * t_s * t_s, 0.04 * t_s)}});
  }
  return out;
}

std::vector<PositionFix> fixes(const std::vector<StampedPose>& poses) {
  std::vector<PositionFix> out;
  for (const StampedPose& p : poses) out.push_back({p.t_s, p.pose.mean.translation()});
  return out;
}

TEST(Alignment, FitOverTheWholeOverlapOrItsFirstSeconds) {
  const Pose2 T_truth_estimate(30.0, -7.0, 12.0 * M_PI / 180.0);
  std::vector<StampedPose> truth = curve(100.0, T_truth_estimate);
  const std::vector<StampedPose> estimate = curve(90.0, Pose2());  // the first 10 s before truth
  // Truth stamps before the estimate's start are not matched; the first is at t = 100 s.
  truth.insert(truth.begin(), {80.0, {Pose2(1e3, 1e3, 0.0)}});
  const Se2Fit whole = fit_se2(shift_times(estimate, 10.0), fixes(truth));
  EXPECT_EQ(whole.positions, 101u);
  EXPECT_NEAR((whole.T_truth_estimate.vector() - T_truth_estimate.vector()).norm(), 0.0, 1e-9);
  // Truth that drifts away after 20 s: only a fit over the first 20 s recovers the motion.
  for (StampedPose& p : truth) {
    if (p.t_s > 120.0) p.pose.mean = Pose2(p.pose.mean.x() + (p.t_s - 120.0), p.pose.mean.y(), 0);
  }
  const Se2Fit first = fit_se2(shift_times(estimate, 10.0), fixes(truth), 20.0);
  EXPECT_EQ(first.positions, 41u);  // stamps 100, 100.5, ..., 120
  EXPECT_NEAR((first.T_truth_estimate.vector() - T_truth_estimate.vector()).norm(), 0.0, 1e-9);
  const Se2Fit drifted = fit_se2(shift_times(estimate, 10.0), fixes(truth));
  EXPECT_GT((drifted.T_truth_estimate.vector() - T_truth_estimate.vector()).norm(), 1.0);
  // A window holding one position only is degenerate.
  EXPECT_THROW(fit_se2(shift_times(estimate, 10.0), fixes(truth), 0.1), std::invalid_argument);
}

TEST(Alignment, TransformTurnsTheCovarianceSoTheNeesIsUnchanged) {
  const Pose2 T(30.0, -7.0, 12.0 * M_PI / 180.0);
  const std::vector<StampedPose> truth = curve(0.0, Pose2());
  StampedPose estimate{10.25, {Pose2(10.5, 1.7, 0.5)}};
  estimate.pose.cov << 0.09, 0.02, 0.001, 0.02, 0.04, -0.002, 0.001, -0.002, 0.0004;
  const StampedPose moved_estimate = transform_poses(T, {estimate})[0];
  const Eigen::Matrix2d R = T.rotation();
  const Eigen::Matrix2d P_xy = R * estimate.pose.cov.topLeftCorner<2, 2>() * R.transpose();
  const Eigen::Vector2d P_xy_yaw = R * estimate.pose.cov.topRightCorner<2, 1>();
  EXPECT_LT((moved_estimate.pose.cov.topLeftCorner<2, 2>() - P_xy).norm(), 1e-15);
  EXPECT_LT((moved_estimate.pose.cov.topRightCorner<2, 1>() - P_xy_yaw).norm(), 1e-15);
  EXPECT_EQ(moved_estimate.pose.cov(2, 2), estimate.pose.cov(2, 2));
  EXPECT_EQ(moved_estimate.t_s, estimate.t_s);
  const double nees = pose_nees({estimate}, truth)[0];
  EXPECT_GT(nees, 1.0);
  EXPECT_NEAR(pose_nees({moved_estimate}, transform_poses(T, truth))[0], nees, 1e-9 * nees);
}

TEST(Alignment, ShiftTimesAddsTheOffset) {
  const std::vector<StampedPose> shifted = shift_times(curve(0.0, Pose2()), -2.5);
  EXPECT_EQ(shifted.front().t_s, -2.5);
  EXPECT_EQ(shifted.back().t_s, 47.5);
}

}  // namespace
}  // namespace msislab
