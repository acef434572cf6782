// The sonar's physics functions with known answers: both beam patterns are 1 on the axis and -3
// dB two-way at half the width, the sinc pattern has its first null where a line aperture has
// it; the pulse and receiver kernel sums to 1, is a box for a pulse alone and decays by e over the
// receiver's time constant; spreading keeps the power; the roughness field has zero mean and unit
// variance everywhere, is continuous, and forgets itself beyond a few correlation lengths.
#include "sim/sonar_physics.hpp"
#include "geometry/angles.hpp"
#include "test_support.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <numeric>
#include <random>
#include <vector>

namespace msislab::sim {
namespace {

TEST(SonarPhysics, PatternsAreMinusThreeDecibelsTwoWayAtHalfTheWidth) {
  const double width_rad = 3.0 * kPi / 180.0;
  for (const BeamPattern shape : {BeamPattern::kGaussian, BeamPattern::kSinc}) {
    EXPECT_DOUBLE_EQ(pattern_1d(0.0, width_rad, shape), 1.0);
    const double edge = pattern_1d(0.5 * width_rad, width_rad, shape);
    EXPECT_NEAR(10.0 * std::log10(edge * edge), -3.0103, 1e-3);
    EXPECT_DOUBLE_EQ(pattern_1d(-0.3 * width_rad, width_rad, shape),
                     pattern_1d(0.3 * width_rad, width_rad, shape));
  }
  // sinc's first null at x = pi: u = pi / 1.0019.
  const double null_rad = 0.5 * width_rad * kPi / 1.0019063576966067;
  EXPECT_NEAR(pattern_1d(null_rad, width_rad, BeamPattern::kSinc), 0.0, 1e-12);
  // Its first sidelobe (x = 4.4934) at -13.3 dB one-way; the Gaussian has no sidelobes: there
  // (u = 4.485) it is down 10 log10(e) ln2 u^2 / 2 = 30.3 dB one-way.
  const double lobe_rad = 0.5 * width_rad * 4.4934 / 1.0019063576966067;
  EXPECT_NEAR(10.0 * std::log10(pattern_1d(lobe_rad, width_rad, BeamPattern::kSinc)), -13.26, 0.01);
  EXPECT_NEAR(10.0 * std::log10(pattern_1d(lobe_rad, width_rad, BeamPattern::kGaussian)), -30.27,
              0.05);
  SonarConfig sonar;
  EXPECT_DOUBLE_EQ(one_way_pattern(0.01, 0.2, sonar),
                   pattern_1d(0.01, 3.0 * kPi / 180.0, sonar.beam_pattern) *
                       pattern_1d(0.2, 35.0 * kPi / 180.0, sonar.beam_pattern));
}

TEST(SonarPhysics, PulseKernelIsABoxThroughAnExponentialTail) {
  SonarConfig sonar;
  sonar.pulse_length_us = 0.0;
  sonar.receiver_time_constant_us = 0.0;
  EXPECT_EQ(pulse_kernel(sonar), std::vector<double>{1.0});
  // A 400 us pulse alone: 0.3 m of range, three bins of 0.1 m, equal.
  sonar.pulse_length_us = 400.0;
  const std::vector<double> box = pulse_kernel(sonar);
  ASSERT_GE(box.size(), 3u);
  EXPECT_NEAR(std::accumulate(box.begin(), box.end(), 0.0), 1.0, 1e-12);
  EXPECT_NEAR(box[1], 1.0 / 3.0, 0.04);
  // The receiver alone (1 ms: c tau / 2 = 0.75 m): the weights fall by e every 7.5 bins.
  sonar.pulse_length_us = 0.0;
  sonar.receiver_time_constant_us = 1000.0;
  const std::vector<double> tail = pulse_kernel(sonar);
  EXPECT_NEAR(std::accumulate(tail.begin(), tail.end(), 0.0), 1.0, 1e-12);
  EXPECT_NEAR(std::log(tail[5] / tail[20]), 15.0 / 7.5, 1e-3);
}

TEST(SonarPhysics, SpreadingKeepsThePowerAndOnlyDelays) {
  const std::vector<double> kernel = {0.5, 0.3, 0.2};
  std::vector<double> power(20, 0.0);
  power[4] = 2.0;
  power[10] = 1.0;
  spread_in_range(kernel, power);
  EXPECT_NEAR(std::accumulate(power.begin(), power.end(), 0.0), 3.0, 1e-12);
  EXPECT_EQ(power[3], 0.0);
  EXPECT_DOUBLE_EQ(power[4], 1.0);
  EXPECT_DOUBLE_EQ(power[5], 0.6);
  EXPECT_DOUBLE_EQ(power[6], 0.4);
  EXPECT_DOUBLE_EQ(power[12], 0.2);
}

TEST(SonarPhysics, RoughnessFieldHasUnitVarianceEverywhereAndAFiniteMemory) {
  std::mt19937_64 rng(testing::seed(3));
  std::uniform_real_distribution<double> coordinate(-500.0, 500.0);
  constexpr double kLength_m = 10.0;
  double sum = 0.0, sum_squares = 0.0, near_product = 0.0, far_product = 0.0;
  constexpr int kSamples = 20000;
  for (int i = 0; i < kSamples; ++i) {
    const Eigen::Vector3f p(static_cast<float>(coordinate(rng)),
                            static_cast<float>(coordinate(rng)),
                            static_cast<float>(coordinate(rng) / 100.0));
    const double g = roughness_field(p, kLength_m);
    sum += g;
    sum_squares += g * g;
    near_product += g * roughness_field(p + Eigen::Vector3f(0.5f, 0.0f, 0.0f), kLength_m);
    far_product += g * roughness_field(p + Eigen::Vector3f(35.0f, 0.0f, 0.0f), kLength_m);
  }
  // Sampling sd of the mean and of the mean square over 20000 draws: 0.007 and 0.01.
  EXPECT_NEAR(sum / kSamples, 0.0, 0.05);
  EXPECT_NEAR(sum_squares / kSamples, 1.0, 0.05);
  EXPECT_GT(near_product / kSamples, 0.9);  // 0.05 correlation lengths apart
  // 3.5 correlation lengths apart: the products' mean has sd about 0.007 (near-independent
  // products of unit variance), so 0.05 is 7 sd.
  EXPECT_NEAR(far_product / kSamples, 0.0, 0.05);
  // On a lattice plane as between them: unit variance along a line that lies in one.
  double line_squares = 0.0;
  for (int i = 0; i < kSamples; ++i) {
    const double g =
        roughness_field(Eigen::Vector3f(20.0f, 0.37f * static_cast<float>(i), -10.0f), kLength_m);
    line_squares += g * g;
  }
  // Not a statistic of the draws: the line is fixed and the field a function of position, so
  // this mean square is one number (740 m of line, about 74 correlation lengths); the bound
  // catches a field whose variance differs on lattice planes (the interpolation's weights wrong).
  EXPECT_NEAR(line_squares / kSamples, 1.0, 0.15);
}

}  // namespace
}  // namespace msislab::sim
