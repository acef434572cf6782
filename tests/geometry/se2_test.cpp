// Tests of the SE(2) pose algebra (geometry/se2.hpp): angle wrapping, every analytic Jacobian
// against central finite differences, the group identities of (+) and (-), and yaw wrap-around.
// Tolerances: finite differences use a step of 1e-6 and must match the analytic Jacobian to 1e-6
// (relative to max(1, |J|)); exact identities hold to 1e-9 m / rad for translations up to 20 m.
#include "geometry/se2.hpp"

#include <gtest/gtest.h>

#include <Eigen/LU>
#include <cmath>
#include <functional>
#include <limits>
#include <random>
#include <vector>
#include "geometry/angles.hpp"
#include "pose_jacobian.hpp"
#include "tests/draws.hpp"

namespace msislab {
namespace {

constexpr double kEps = std::numeric_limits<double>::epsilon();
using testing::kFdStep;
using testing::numeric_jacobian;
constexpr double kJacobianTol = 1e-6;  ///< relative to max(1, max |J_ij|)
constexpr double kIdentityTol = 1e-9;  ///< m or rad

/// True when the angle lies in (-pi, pi].
bool in_half_open_range(double angle_rad) { return angle_rad > -kPi && angle_rad <= kPi; }

/// Angular distance between two angles, in [0, pi].
double angle_distance(double a_rad, double b_rad) {
  return std::abs(normalize_angle(a_rad - b_rad));
}

// ---------------------------------------------------------------------------------------------
// normalize_angle

TEST(NormalizeAngle, ZeroAndTinyAnglesAreUnchanged) {
  EXPECT_EQ(normalize_angle(0.0), 0.0);
  EXPECT_EQ(normalize_angle(kEps), kEps);
  EXPECT_EQ(normalize_angle(-kEps), -kEps);
  EXPECT_EQ(normalize_angle(1e-300), 1e-300);
  EXPECT_EQ(normalize_angle(-1e-300), -1e-300);
}

TEST(NormalizeAngle, PiStaysAndMinusPiMapsToPi) {
  EXPECT_EQ(normalize_angle(kPi), kPi);
  EXPECT_EQ(normalize_angle(-kPi), kPi);
}

TEST(NormalizeAngle, JustInsideAndJustOutsidePi) {
  const double below_pi = std::nextafter(kPi, 0.0);
  const double above_pi = std::nextafter(kPi, 4.0);
  EXPECT_EQ(normalize_angle(below_pi), below_pi);
  EXPECT_EQ(normalize_angle(-below_pi), -below_pi);
  // Just above pi wraps to just above -pi, and just below -pi wraps to just below pi.
  EXPECT_TRUE(in_half_open_range(normalize_angle(above_pi)));
  EXPECT_LT(normalize_angle(above_pi), -kPi + 1e-14);
  EXPECT_TRUE(in_half_open_range(normalize_angle(-above_pi)));
  EXPECT_GT(normalize_angle(-above_pi), kPi - 1e-14);

  EXPECT_NEAR(normalize_angle(kPi + 1e-6), -kPi + 1e-6, 1e-15);
  EXPECT_NEAR(normalize_angle(-kPi - 1e-6), kPi - 1e-6, 1e-15);
  EXPECT_EQ(normalize_angle(kPi - 1e-6), kPi - 1e-6);
  EXPECT_EQ(normalize_angle(-kPi + 1e-6), -kPi + 1e-6);
}

TEST(NormalizeAngle, OddMultiplesOfPiLandOnPi) {
  for (const double k : {3.0, -3.0, 5.0, -5.0, 101.0, -101.0}) {
    const double wrapped = normalize_angle(k * kPi);
    EXPECT_TRUE(in_half_open_range(wrapped)) << "k = " << k;
    EXPECT_NEAR(std::abs(wrapped), kPi, 1e-12) << "k = " << k;
  }
}

TEST(NormalizeAngle, EvenMultiplesOfPiLandOnZero) {
  for (const double k : {2.0, -2.0, 4.0, -4.0, 1000.0, -1000.0}) {
    EXPECT_NEAR(normalize_angle(k * kPi), 0.0, 1e-12) << "k = " << k;
  }
}

TEST(NormalizeAngle, LargeMultiplesKeepTheOffset) {
  // Tolerance grows with the input magnitude: k * 2pi itself carries a rounding error of ulp(k pi).
  for (const double turns : {1.0, -1.0, 7.0, -7.0, 1e3, -1e3, 1e6, -1e6}) {
    for (const double offset : {0.0, 0.25, -0.25, 3.0, -3.0}) {
      const double angle = offset + turns * 2.0 * kPi;
      const double wrapped = normalize_angle(angle);
      EXPECT_TRUE(in_half_open_range(wrapped)) << angle;
      EXPECT_NEAR(wrapped, offset, 1e-15 * std::abs(angle) + 1e-15) << angle;
    }
  }
}

TEST(NormalizeAngle, ResultIsInRangeAndDiffersByWholeTurns) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> angle(-100.0, 100.0);
  for (int i = 0; i < 1000; ++i) {
    const double a = angle(rng);
    const double wrapped = normalize_angle(a);
    ASSERT_TRUE(in_half_open_range(wrapped)) << a;
    const double turns = (a - wrapped) / (2.0 * kPi);
    EXPECT_NEAR(turns, std::round(turns), 1e-12) << a;
  }
}

// ---------------------------------------------------------------------------------------------
// Pose2 basics

TEST(Pose2, ConstructorsNormalizeYaw) {
  EXPECT_EQ(Pose2().vector(), Eigen::Vector3d::Zero());
  const Pose2 p(1.0, -2.0, 3.0 * kPi / 2.0);
  EXPECT_EQ(p.x(), 1.0);
  EXPECT_EQ(p.y(), -2.0);
  EXPECT_NEAR(p.yaw(), -kPi / 2.0, 1e-15);
  EXPECT_EQ(Pose2(Eigen::Vector3d(1.0, -2.0, 3.0 * kPi / 2.0)).vector(), p.vector());
  EXPECT_EQ(Pose2(0.0, 0.0, -kPi).yaw(), kPi);
  EXPECT_EQ(p.translation(), Eigen::Vector2d(1.0, -2.0));
}

TEST(Pose2, RotationIsCounterClockwise) {
  const Eigen::Matrix2d R = Pose2(0.0, 0.0, kPi / 2.0).rotation();
  // The vehicle's x axis (forward) points along the parent's y axis after a +90 deg yaw.
  EXPECT_TRUE((R * Eigen::Vector2d::UnitX()).isApprox(Eigen::Vector2d::UnitY(), 1e-15));
  EXPECT_NEAR(R.determinant(), 1.0, 1e-15);
}

// ---------------------------------------------------------------------------------------------
// Jacobians against central finite differences

/// The poses at which every Jacobian is checked: special yaws (0, +-eps, +-pi, within one step of
/// +-pi so the perturbed yaw wraps) and 200 random poses from a fixed seed with yaw over the
/// whole circle.
std::vector<Pose2> test_poses() {
  std::vector<Pose2> poses;
  const double yaws[] = {0.0,
                         kEps,
                         -kEps,
                         1e-9,
                         -1e-9,
                         kPi,
                         -kPi,
                         kPi - 1e-7,
                         -kPi + 1e-7,
                         kPi - kFdStep,
                         kPi / 2.0,
                         -kPi / 2.0,
                         std::nextafter(kPi, 0.0)};
  for (const double yaw : yaws) {
    poses.emplace_back(0.0, 0.0, yaw);
    poses.emplace_back(3.5, -1.25, yaw);
  }
  std::mt19937 rng(20240601);
  std::uniform_real_distribution<double> xy_m(-10.0, 10.0);
  std::uniform_real_distribution<double> yaw_rad(-kPi, kPi);
  for (int i = 0; i < 200; ++i) {
    const double yaw = yaw_rad(rng), y = xy_m(rng), x = xy_m(rng);  // tests/draws.hpp's order
    poses.emplace_back(x, y, yaw);
  }
  return poses;
}

/// Numerical Jacobian of a 2-vector-valued function of a pose.
Matrix23d numeric_point_jacobian(const std::function<Eigen::Vector2d(const Pose2&)>& f,
                                 const Pose2& x) {
  Matrix23d J;
  for (int i = 0; i < 3; ++i) {
    const Eigen::Vector3d step = kFdStep * Eigen::Vector3d::Unit(i);
    J.col(i) = (f(Pose2(x.vector() + step)) - f(Pose2(x.vector() - step))) / (2.0 * kFdStep);
  }
  return J;
}

template <typename Derived1, typename Derived2>
::testing::AssertionResult jacobians_match(const Eigen::MatrixBase<Derived1>& analytic,
                                           const Eigen::MatrixBase<Derived2>& numeric) {
  const double scale = std::max(1.0, analytic.cwiseAbs().maxCoeff());
  const double error = (analytic - numeric).cwiseAbs().maxCoeff();
  if (error <= kJacobianTol * scale) return ::testing::AssertionSuccess();
  return ::testing::AssertionFailure() << "max error " << error << "\nanalytic:\n"
                                       << analytic << "\nnumeric:\n"
                                       << numeric;
}

/// Every test pose paired with a partner from the same list (a shifted index), so both
/// arguments of a binary operation sweep the special and random yaws.
struct PosePair {
  Pose2 first;
  Pose2 second;
};

std::vector<PosePair> test_pose_pairs() {
  const std::vector<Pose2> poses = test_poses();
  std::vector<PosePair> pairs;
  for (std::size_t i = 0; i < poses.size(); ++i) {
    pairs.push_back({poses[i], poses[(i * 7 + 3) % poses.size()]});
    pairs.push_back({poses[i], poses[i]});
  }
  return pairs;
}

TEST(Pose2Jacobians, ComposeJ1PlusAndJ2Plus) {
  for (const auto& pair : test_pose_pairs()) {
    const Pose2& x_ab = pair.first;
    const Pose2& x_bc = pair.second;
    Eigen::Matrix3d J_out_ab;
    Eigen::Matrix3d J_out_bc;
    x_ab.compose(x_bc, &J_out_ab, &J_out_bc);
    const auto vary_ab = [&](const Pose2& p) { return p.compose(x_bc); };
    const auto vary_bc = [&](const Pose2& p) { return x_ab.compose(p); };
    EXPECT_TRUE(jacobians_match(J_out_ab, numeric_jacobian(vary_ab, x_ab)))
        << "x_ab " << x_ab.vector().transpose() << " x_bc " << x_bc.vector().transpose();
    EXPECT_TRUE(jacobians_match(J_out_bc, numeric_jacobian(vary_bc, x_bc)))
        << "x_ab " << x_ab.vector().transpose() << " x_bc " << x_bc.vector().transpose();
  }
}

TEST(Pose2Jacobians, ComposeJacobiansAreOptionalAndIndependent) {
  const Pose2 x_ab(1.0, 2.0, 0.3);
  const Pose2 x_bc(-0.5, 4.0, -2.9);
  Eigen::Matrix3d J1_both;
  Eigen::Matrix3d J2_both;
  Eigen::Matrix3d J1_only;
  Eigen::Matrix3d J2_only;
  const Pose2 with_both = x_ab.compose(x_bc, &J1_both, &J2_both);
  const Pose2 with_j1 = x_ab.compose(x_bc, &J1_only, nullptr);
  const Pose2 with_j2 = x_ab.compose(x_bc, nullptr, &J2_only);
  const Pose2 with_none = x_ab.compose(x_bc);
  EXPECT_EQ(J1_both, J1_only);
  EXPECT_EQ(J2_both, J2_only);
  EXPECT_EQ(with_both.vector(), with_none.vector());
  EXPECT_EQ(with_j1.vector(), with_none.vector());
  EXPECT_EQ(with_j2.vector(), with_none.vector());
}

TEST(Pose2Jacobians, InverseJMinus) {
  for (const Pose2& x_ab : test_poses()) {
    Eigen::Matrix3d J_out_ab;
    x_ab.inverse(&J_out_ab);
    const auto f = [](const Pose2& p) { return p.inverse(); };
    EXPECT_TRUE(jacobians_match(J_out_ab, numeric_jacobian(f, x_ab)))
        << "x_ab " << x_ab.vector().transpose();
  }
}

TEST(Pose2Jacobians, BetweenBothArguments) {
  for (const auto& pair : test_pose_pairs()) {
    const Pose2& x_ab = pair.first;
    const Pose2& x_ac = pair.second;
    Eigen::Matrix3d J_out_ab;
    Eigen::Matrix3d J_out_ac;
    x_ab.between(x_ac, &J_out_ab, &J_out_ac);
    const auto vary_ab = [&](const Pose2& p) { return p.between(x_ac); };
    const auto vary_ac = [&](const Pose2& p) { return x_ab.between(p); };
    EXPECT_TRUE(jacobians_match(J_out_ab, numeric_jacobian(vary_ab, x_ab)))
        << "x_ab " << x_ab.vector().transpose() << " x_ac " << x_ac.vector().transpose();
    EXPECT_TRUE(jacobians_match(J_out_ac, numeric_jacobian(vary_ac, x_ac)))
        << "x_ab " << x_ab.vector().transpose() << " x_ac " << x_ac.vector().transpose();

    // Each output alone equals the one computed together with the other.
    Eigen::Matrix3d J_ab_only;
    Eigen::Matrix3d J_ac_only;
    x_ab.between(x_ac, &J_ab_only, nullptr);
    x_ab.between(x_ac, nullptr, &J_ac_only);
    EXPECT_EQ(J_ab_only, J_out_ab);
    EXPECT_EQ(J_ac_only, J_out_ac);
  }
}

TEST(Pose2Jacobians, TransformPoseAndPoint) {
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> coord_m(-20.0, 20.0);
  for (const Pose2& x_ab : test_poses()) {
    const Eigen::Vector2d p_b = draws_last_first<2>([&] { return coord_m(rng); });
    Matrix23d J_out_pose;
    Eigen::Matrix2d J_out_point;
    x_ab.transform(p_b, &J_out_pose, &J_out_point);

    const auto vary_pose = [&](const Pose2& x) { return x.transform(p_b); };
    EXPECT_TRUE(jacobians_match(J_out_pose, numeric_point_jacobian(vary_pose, x_ab)))
        << "x_ab " << x_ab.vector().transpose() << " p_b " << p_b.transpose();

    Eigen::Matrix2d J_point_numeric;
    for (int i = 0; i < 2; ++i) {
      const Eigen::Vector2d step = kFdStep * Eigen::Vector2d::Unit(i);
      J_point_numeric.col(i) =
          (x_ab.transform(p_b + step) - x_ab.transform(p_b - step)) / (2.0 * kFdStep);
    }
    EXPECT_TRUE(jacobians_match(J_out_point, J_point_numeric))
        << "x_ab " << x_ab.vector().transpose() << " p_b " << p_b.transpose();
  }
}

TEST(Pose2Jacobians, ClosedFormsAtKnownPose) {
  // x_ab = [1, 2, pi/2], x_bc = [3, 0, 0]: x_bc's offset seen in a is [0, 3].
  const Pose2 x_ab(1.0, 2.0, kPi / 2.0);
  const Pose2 x_bc(3.0, 0.0, 0.0);
  Eigen::Matrix3d J1;
  Eigen::Matrix3d J2;
  const Pose2 x_ac = x_ab.compose(x_bc, &J1, &J2);
  EXPECT_TRUE(x_ac.vector().isApprox(Eigen::Vector3d(1.0, 5.0, kPi / 2.0), 1e-15));
  Eigen::Matrix3d J1_expected;
  J1_expected << 1, 0, -3, 0, 1, 0, 0, 0, 1;
  Eigen::Matrix3d J2_expected;
  J2_expected << 0, -1, 0, 1, 0, 0, 0, 0, 1;
  EXPECT_LT((J1 - J1_expected).cwiseAbs().maxCoeff(), 1e-15);
  EXPECT_LT((J2 - J2_expected).cwiseAbs().maxCoeff(), 1e-15);

  Eigen::Matrix3d J_inv;
  const Pose2 x_ba = x_ab.inverse(&J_inv);
  // x_ba = [-x c - y s, x s - y c, -yaw] = [-2, 1, -pi/2].
  EXPECT_LT(pose_difference(x_ba, Pose2(-2.0, 1.0, -kPi / 2.0)).norm(), 1e-15);
  Eigen::Matrix3d J_inv_expected;
  J_inv_expected << 0, -1, 1, 1, 0, 2, 0, 0, -1;
  EXPECT_LT((J_inv - J_inv_expected).cwiseAbs().maxCoeff(), 1e-15);
}

TEST(Pose2Jacobians, BetweenClosedFormOfDocs) {
  // docs/pose_algebra.md: with c, s of yaw_ab and x_bc = between(x_ab, x_ac),
  // J_out_ab = [-c -s y_bc; s -c -x_bc; 0 0 -1], J_out_ac = [c s 0; -s c 0; 0 0 1].
  for (const auto& pair : test_pose_pairs()) {
    const Pose2& x_ab = pair.first;
    const Pose2& x_ac = pair.second;
    Eigen::Matrix3d J_out_ab;
    Eigen::Matrix3d J_out_ac;
    const Pose2 x_bc = x_ab.between(x_ac, &J_out_ab, &J_out_ac);
    const double c = std::cos(x_ab.yaw());
    const double s = std::sin(x_ab.yaw());
    Eigen::Matrix3d J_ab_expected;
    J_ab_expected << -c, -s, x_bc.y(), s, -c, -x_bc.x(), 0, 0, -1;
    Eigen::Matrix3d J_ac_expected;
    J_ac_expected << c, s, 0, -s, c, 0, 0, 0, 1;
    EXPECT_LT((J_out_ab - J_ab_expected).cwiseAbs().maxCoeff(), kIdentityTol);
    EXPECT_LT((J_out_ac - J_ac_expected).cwiseAbs().maxCoeff(), kIdentityTol);
  }
}

// ---------------------------------------------------------------------------------------------
// Algebraic identities

::testing::AssertionResult poses_near(const Pose2& a, const Pose2& b, double tol = kIdentityTol) {
  const double error = pose_difference(a, b).cwiseAbs().maxCoeff();
  if (error <= tol) return ::testing::AssertionSuccess();
  return ::testing::AssertionFailure() << a.vector().transpose() << " vs " << b.vector().transpose()
                                       << " (error " << error << ")";
}

TEST(Pose2Identities, ComposeWithInverseIsIdentity) {
  for (const Pose2& x : test_poses()) {
    EXPECT_TRUE(poses_near(x.compose(x.inverse()), Pose2()));
    EXPECT_TRUE(poses_near(x.inverse().compose(x), Pose2()));
    EXPECT_TRUE(in_half_open_range(x.compose(x.inverse()).yaw()));
  }
}

TEST(Pose2Identities, InverseIsAnInvolution) {
  for (const Pose2& x : test_poses()) {
    EXPECT_TRUE(poses_near(x.inverse().inverse(), x));
  }
}

TEST(Pose2Identities, IdentityIsNeutral) {
  for (const Pose2& x : test_poses()) {
    EXPECT_TRUE(poses_near(x.compose(Pose2()), x, 0.0));
    EXPECT_TRUE(poses_near(Pose2().compose(x), x, 0.0));
  }
}

TEST(Pose2Identities, ComposeIsAssociative) {
  const std::vector<Pose2> poses = test_poses();
  for (std::size_t i = 0; i < poses.size(); ++i) {
    const Pose2& a = poses[i];
    const Pose2& b = poses[(i + 5) % poses.size()];
    const Pose2& c = poses[(i * 3 + 1) % poses.size()];
    EXPECT_TRUE(poses_near(a.compose(b).compose(c), a.compose(b.compose(c))));
  }
}

TEST(Pose2Identities, InverseOfComposeIsReversedComposeOfInverses) {
  const std::vector<Pose2> poses = test_poses();
  for (std::size_t i = 0; i < poses.size(); ++i) {
    const Pose2& a = poses[i];
    const Pose2& b = poses[(i + 11) % poses.size()];
    EXPECT_TRUE(poses_near(a.compose(b).inverse(), b.inverse().compose(a.inverse())));
  }
}

TEST(Pose2Identities, BetweenRecoversTheRelativePose) {
  for (const auto& [x_ab, x_bc] : test_pose_pairs()) {
    const Pose2 x_ac = x_ab.compose(x_bc);
    EXPECT_TRUE(poses_near(x_ab.between(x_ac), x_bc));
    EXPECT_TRUE(poses_near(x_ab.between(x_ac), x_ab.inverse().compose(x_ac), 0.0));
    EXPECT_TRUE(poses_near(x_ab.between(x_ab), Pose2()));
  }
}

TEST(Pose2Identities, TransformEqualsComposeWithZeroYawPose) {
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> coord_m(-20.0, 20.0);
  for (const Pose2& x_ab : test_poses()) {
    const Eigen::Vector2d p_b = draws_last_first<2>([&] { return coord_m(rng); });
    const Eigen::Vector2d p_a = x_ab.transform(p_b);
    const Pose2 x_ap = x_ab.compose(Pose2(p_b.x(), p_b.y(), 0.0));
    EXPECT_LT((p_a - x_ap.translation()).cwiseAbs().maxCoeff(), kIdentityTol);
    // Transforming back with the inverse recovers the point.
    EXPECT_LT((x_ab.inverse().transform(p_a) - p_b).cwiseAbs().maxCoeff(), kIdentityTol);
  }
}

TEST(Pose2Identities, OperatorsMatchNamedFunctions) {
  for (const auto& [a, b] : test_pose_pairs()) {
    EXPECT_EQ((a + b).vector(), a.compose(b).vector());
    EXPECT_EQ((-a).vector(), a.inverse().vector());
    EXPECT_EQ((-a + b).vector(), a.between(b).vector());
  }
}

TEST(Pose2Identities, PoseDifferenceWrapsTheAngle) {
  const Pose2 a(1.0, 2.0, kPi - 0.1);
  const Pose2 b(0.5, 3.0, -kPi + 0.1);
  const Eigen::Vector3d d = pose_difference(a, b);
  EXPECT_DOUBLE_EQ(d.x(), 0.5);
  EXPECT_DOUBLE_EQ(d.y(), -1.0);
  EXPECT_NEAR(d.z(), -0.2, 1e-12);
  EXPECT_NEAR(pose_difference(b, a).z(), 0.2, 1e-12);
}

// ---------------------------------------------------------------------------------------------
// Wrap-around

TEST(Pose2WrapAround, ComposedYawPastPiIsNormalized) {
  const Pose2 x_ac = Pose2(0.0, 0.0, 3.0).compose(Pose2(0.0, 0.0, 0.5));
  EXPECT_TRUE(in_half_open_range(x_ac.yaw()));
  EXPECT_NEAR(x_ac.yaw(), 3.5 - 2.0 * kPi, 1e-15);

  const Pose2 x_ac_negative = Pose2(0.0, 0.0, -3.0).compose(Pose2(0.0, 0.0, -0.5));
  EXPECT_TRUE(in_half_open_range(x_ac_negative.yaw()));
  EXPECT_NEAR(x_ac_negative.yaw(), 2.0 * kPi - 3.5, 1e-15);
}

TEST(Pose2WrapAround, HalfTurnsSumToAFullTurn) {
  const Pose2 half_turn(0.0, 0.0, kPi);
  EXPECT_NEAR((half_turn + half_turn).yaw(), 0.0, 1e-15);
  EXPECT_EQ((-half_turn).yaw(), kPi);  // -pi is reported as +pi
  const Pose2 two_quarters = Pose2(0.0, 0.0, kPi / 2.0) + Pose2(0.0, 0.0, kPi / 2.0);
  EXPECT_EQ(two_quarters.yaw(), kPi);
  const Pose2 minus_two_quarters = Pose2(0.0, 0.0, -kPi / 2.0) + Pose2(0.0, 0.0, -kPi / 2.0);
  EXPECT_EQ(minus_two_quarters.yaw(), kPi);
}

TEST(Pose2WrapAround, LongChainOfSmallTurnsStaysInRange) {
  // 1000 steps of 1 m forward and 0.1 rad left: every intermediate yaw is normalized, and the
  // chain matches the closed form of a circle of radius 1 / (2 sin(0.05)) to 1e-9.
  const Pose2 step(1.0, 0.0, 0.1);
  Pose2 x_world_vehicle;
  double yaw_unwrapped_rad = 0.0;
  for (int i = 0; i < 1000; ++i) {
    x_world_vehicle = x_world_vehicle + step;
    yaw_unwrapped_rad += 0.1;
    ASSERT_TRUE(in_half_open_range(x_world_vehicle.yaw()));
    ASSERT_LT(angle_distance(x_world_vehicle.yaw(), yaw_unwrapped_rad), 1e-9);
  }
  // Step k (k = 0..n-1) moves 1 m along heading 0.1 k; the sum of those unit vectors is
  // sin(n h) / sin(h) [cos((n-1) h), sin((n-1) h)] with h = 0.05.
  const double n = 1000.0;
  const double half = 0.05;
  const double chord_scale = std::sin(n * half) / std::sin(half);
  const Eigen::Vector2d expected(chord_scale * std::cos((n - 1.0) * half),
                                 chord_scale * std::sin((n - 1.0) * half));
  EXPECT_LT((x_world_vehicle.translation() - expected).norm(), 1e-9);
}

}  // namespace
}  // namespace msislab
