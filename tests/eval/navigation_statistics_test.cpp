// Navigation statistics on synthetic data with known answers: white noise of known sigma from
// sample differences, dropout clustering, heading noise across the +-pi wrap, the compass
// comparison, a known GPS lag and tether, and dead-reckoning drift from a known heading offset.
#include "eval/navigation_statistics.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <iterator>
#include <random>

#include "geometry/angles.hpp"
#include "geometry/se2.hpp"
#include "test_support.hpp"
#include "tests/draws.hpp"

namespace msislab {
namespace {

/// A vehicle at 0.2 m/s whose yaw rate swings as turn_rate sin(2 pi t / 200) (curves both ways),
/// with truth at 10 Hz, exact DVL at 1.5 Hz and heading at 10 Hz (plus an optional offset).
struct SyntheticRun {
  std::vector<PositionFix> truth;
  std::vector<double> yaw_rad;  ///< at the truth stamps
  NavigationLog log;
};

SyntheticRun synthetic_run(double duration_s, double heading_offset_rad = 0.0,
                           double turn_rate_radps = 0.05) {
  SyntheticRun run;
  const double dt = 0.01, speed = 0.2;
  Eigen::Vector2d p = Eigen::Vector2d::Zero();
  double yaw = 0.3;
  for (int k = 0; k * dt <= duration_s; ++k) {
    const double t = k * dt;
    if (k % 10 == 0) {
      run.truth.push_back({t, p});
      run.yaw_rad.push_back(yaw);
      run.log.heading.push_back({t, normalize_angle(yaw + heading_offset_rad)});
    }
    if (k % 200 == 0 || k % 200 == 67 || k % 200 == 133) {  // 1.5 Hz on average
      run.log.dvl.push_back({t, Eigen::Vector2d(speed, 0.0)});
    }
    const double rate = turn_rate_radps * std::sin(2.0 * M_PI * t / 200.0);
    p += speed * dt * Eigen::Vector2d(std::cos(yaw), std::sin(yaw));
    yaw = normalize_angle(yaw + rate * dt);
  }
  return run;
}

TEST(DifferenceNoise, RecoversWhiteNoiseOnASmoothSignal) {
  std::mt19937 rng(testing::seed(7));
  std::normal_distribution<double> n01(0.0, 1.0);
  std::vector<double> x;
  for (int i = 0; i < 20000; ++i) x.push_back(std::sin(i * 0.01) + 0.2 * n01(rng));
  for (const int order : {1, 2}) {
    const DifferenceNoise noise = difference_noise(x, order);
    EXPECT_NEAR(noise.sigma_sd, 0.2, 0.004) << "order " << order;  // 2% (sd's error 0.5-1%)
    EXPECT_NEAR(noise.sigma_mad, 0.2, 0.006) << "order " << order;
    EXPECT_NEAR(noise.kurtosis, 3.0, 0.2) << "order " << order;
  }
}

TEST(DvlNoise, RecoversSigmaRateAndSkipsGaps) {
  std::mt19937 rng(testing::seed(8));
  std::normal_distribution<double> n01(0.0, 1.0);
  std::vector<DvlVelocity> dvl;
  for (int i = 0; i < 20000; ++i) {
    if (i % 50 == 7) continue;  // a dropout: the difference across it is not used
    // The surge steps by 1 m/s at each dropout: a difference taken across one would show it.
    const double surge = 0.2 + ((i + 43) / 50 % 2 ? 1.0 : 0.0);
    dvl.push_back(
        {i / 1.5, Eigen::Vector2d(surge, 0.0) + draws_last_first<2>([&] {
                                                  return n01(rng);
                                                }).cwiseProduct(Eigen::Vector2d(0.1, 0.15))});
  }
  const DvlNoiseStatistics s = dvl_noise_statistics(dvl);
  EXPECT_NEAR(s.rate_hz, 1.5, 1e-9);
  // About 19,200 first differences: sigma from their sd has a relative standard error of
  // sqrt(0.75 / n) = 0.62 % (the differences' lag-1 correlation -1/2), from their MAD 0.87 %
  // (both measured over 120 simulated series, the sd's as the formula says). The bounds sit at
  // 3.2, 4.6 and 3.2 standard errors: together they fail a correct stream about 0.3 % of the
  // time, and a sigma 3 % off fails the sd bound nine times in ten.
  EXPECT_NEAR(s.surge_mps.sigma_sd, 0.1, 0.002);
  EXPECT_NEAR(s.surge_mps.sigma_mad, 0.1, 0.004);
  EXPECT_NEAR(s.sway_mps.sigma_sd, 0.15, 0.003);
}

TEST(Dropouts, IndependentLossesAreNotClustered) {
  std::mt19937 rng(testing::seed(9));
  std::bernoulli_distribution loss(0.02);
  std::vector<DvlRow> rows;
  for (int i = 0; i < 30000; ++i) rows.push_back({i / 1.5, !loss(rng), std::nullopt});
  const DropoutStatistics s = dropout_statistics(rows, 1.5);
  // The fraction is binomial, standard error sqrt(0.02 0.98 / 30000) = 0.00081: the bound at
  // 3.3 of them (two-sided 0.08 %; it was 0.002, 2.5 of them, failing 1.3 % of correct streams).
  // About 590 bursts of geometric length, mean 1 / 0.98 and sd 0.144: the mean's standard error
  // 0.0059, the bound at 3.4 of them (0.07 %). A loss probability of 0.024 fails nine times in ten.
  EXPECT_NEAR(s.fraction, 0.02, 0.0027);
  EXPECT_NEAR(s.mean_burst_rows, 1.0 / 0.98, 0.02);
  ASSERT_EQ(s.dispersion.size(), kDispersionBlocks.size());
  // The index's sampling sd is about sqrt(2 / blocks): 0.02, 0.06, 0.2.
  EXPECT_NEAR(s.dispersion[0], 0.98, 0.06);
  EXPECT_NEAR(s.dispersion[1], 0.98, 0.15);
  EXPECT_NEAR(s.dispersion[2], 0.98, 0.5);
}

TEST(Dropouts, BurstsRaiseTheDispersionAndTheDegradedState) {
  std::vector<DvlRow> rows;
  for (int i = 0; i < 30000; ++i) {
    const bool in_burst = i % 300 < 30;  // 30 rows of every 300 lose every other sample
    rows.push_back({i / 1.5, !(in_burst && i % 2 == 0), std::nullopt});
  }
  const DropoutStatistics s = dropout_statistics(rows, 1.5);
  EXPECT_NEAR(s.fraction, 0.05, 1e-9);
  EXPECT_GT(s.dispersion[1], 5.0);
  EXPECT_NEAR(s.model.degraded_loss_probability, 0.5, 0.03);
  EXPECT_NEAR(s.model.degraded_fraction, 0.1, 0.01);
  EXPECT_NEAR(s.degraded_mean_s, 20.0, 2.0);
}

TEST(HeadingNoise, RecoversSigmaAcrossTheWrap) {
  std::mt19937 rng(testing::seed(10));
  std::normal_distribution<double> n01(0.0, 1.0);
  std::vector<HeadingReading> heading;
  for (int i = 0; i < 36000; ++i) {  // 1 hour at 10 Hz turning at 3 deg/s: 30 wraps
    const double yaw = 3.0 * kDegToRad * i / 10.0 + 0.05 * kDegToRad * n01(rng);
    heading.push_back({i / 10.0, normalize_angle(yaw)});
  }
  const HeadingNoiseStatistics s = heading_noise_statistics(heading);
  EXPECT_NEAR(s.rate_hz, 10.0, 1e-6);
  // About 36,000 second differences: sigma from their sd has a relative standard error of 0.50 %,
  // from their MAD 0.73 % (measured over 120 simulated series; the sd's formula gives 0.52 %).
  // The bounds at 4.0 and 4.1 standard errors fail a correct stream less than 0.01 % of the
  // time; a sigma 3 % off fails the sd bound nine times in ten.
  EXPECT_NEAR(s.noise_deg.sigma_sd, 0.05, 0.001);
  EXPECT_NEAR(s.noise_deg.sigma_mad, 0.05, 0.0015);
  // 3 deg/s over a 13.8 s revolution: 41.4 deg, across the wraps. Not a bound on noise: the
  // median of about 260 revolutions' turns moves by some 0.006 deg standard error; 0.3 deg is a
  // revolution taken 0.1 s off, or a wrap lost.
  EXPECT_NEAR(s.turn_per_revolution_deg, 41.4, 0.3);
}

TEST(HeadingNoise, TurnPerRevolutionIsTheMedianHeadingChange) {
  // Straight for 10 minutes, then 5 minutes of 1 deg/s: most revolutions do not turn.
  std::vector<HeadingReading> heading;
  double yaw_deg = 0.0;
  for (int i = 0; i < 9000; ++i) {
    if (i >= 6000) yaw_deg += 0.1;
    heading.push_back({i / 10.0, normalize_angle(yaw_deg * kDegToRad)});
  }
  EXPECT_NEAR(heading_noise_statistics(heading).turn_per_revolution_deg, 0.0, 1e-9);
  for (int i = 0; i < 9000; ++i) heading[i].yaw_rad = normalize_angle(0.1 * i * kDegToRad);
  EXPECT_NEAR(heading_noise_statistics(heading).turn_per_revolution_deg, 13.8, 0.11);
}

TEST(Compasses, RecoversOffsetAndDeviationCurve) {
  const SyntheticRun run = synthetic_run(3000.0);
  std::mt19937 rng(testing::seed(11));
  std::normal_distribution<double> n01(0.0, 1.0);
  std::vector<DvlRow> rows;
  for (const DvlVelocity& d : run.log.dvl) {
    const double yaw = nearest_heading(run.log.heading, d.t_s).yaw_rad;
    const double error_deg = -61.5 + 4.0 * std::cos(yaw) + 3.0 * std::sin(yaw) + 1.0 * n01(rng);
    rows.push_back({d.t_s, true, normalize_angle(yaw + error_deg * kDegToRad)});
  }
  const std::optional<CompassComparison> c = compare_compasses(run.log.heading, rows);
  ASSERT_TRUE(c);
  // About 4,500 readings with 1 deg white noise. Measured over 40 seed offsets (stride 1000):
  // the offset's standard deviation 0.022 deg, the deviation amplitude's 0.018 deg, the residual
  // sd's 0.0073 deg, so the bounds sit at 4.6, 5.5 and 6.8 of them (under 0.001 % together,
  // were the estimates normal); an offset 0.13 deg off fails nine times in ten.
  EXPECT_NEAR(c->offset_deg, -61.5, 0.1);
  EXPECT_NEAR(c->deviation_amplitude_deg, 5.0, 0.1);
  EXPECT_NEAR(c->residual_sd_deg, 1.0, 0.05);  // 6.8 sd
  // The residual's means over the 15 blocks of 200 s (300 readings each) spread as
  // 1 / sqrt(300) = 0.058 deg, their sample sd as 0.058 sqrt(chi2(14) / 14): its 0.999 quantile
  // is 0.093 deg, so the bound 0.1. A compass random walk of 0.005 deg/sqrt(s) spreads them by
  // about 0.005 sqrt(3000 / 6) = 0.11 deg more and is caught. (Was 0.2, failing 9 of 20 seed
  // offsets: the log's last reading made a block of its own, which compare_compasses now joins
  // to the block before.)
  EXPECT_LT(c->block_mean_sd_deg, 0.1);  // the chi-square 0.999 quantile above
  for (DvlRow& row : rows) row.compass_yaw_rad.reset();
  EXPECT_FALSE(compare_compasses(run.log.heading, rows));
}

TEST(TowedBuoy, TrailsByTheTetherAndWaitsWhenTheVehicleStops) {
  std::vector<PositionFix> vehicle;
  for (int i = 0; i <= 1000; ++i) vehicle.push_back({i * 0.1, {std::min(i, 600) * 0.02, 0.0}});
  const std::vector<PositionFix> buoy = towed_buoy(vehicle, 3.0);
  EXPECT_DOUBLE_EQ(buoy[100].p_world_m.x(), 0.0);  // 2 m out: still slack
  EXPECT_NEAR(buoy[600].p_world_m.x(), 12.0 - 3.0, 1e-9);
  EXPECT_NEAR(buoy[1000].p_world_m.x(), 9.0, 1e-9);  // the vehicle stopped at 12 m
}

TEST(GpsStatistics, RecoversAKnownLagTetherAndWhiteNoise) {
  const SyntheticRun run = synthetic_run(2400.0);
  std::mt19937 rng(testing::seed(12));
  std::normal_distribution<double> n01(0.0, 1.0);
  // GPS at 1 Hz: (a) the vehicle 10 s late, (b) a buoy on a 3 m tether; 0.05 m white noise.
  std::vector<PositionFix> late, towed;
  const std::vector<PositionFix> buoy = towed_buoy(run.truth, 3.0);
  for (std::size_t i = 100; i < run.truth.size(); i += 10) {
    const Eigen::Vector2d noise = 0.05 * draws_last_first<2>([&] { return n01(rng); });
    late.push_back({run.truth[i].t_s, run.truth[i - 100].p_world_m + noise});
    towed.push_back({run.truth[i].t_s, buoy[i].p_world_m + noise});
  }
  // Over 100 seed offsets (k x 1000): the lag 9.96 s, sd 0.009 s, so 0.5 s is 50 sd and catches
  // an epoch misread by half a second; the white noise's sd 0.0500 and 0.0500 m, sd 0.00095 and
  // 0.0010 m, so 0.0035 is 3.4 sd or more (two-sided 0.07 % each) and catches noise 10 % off
  // (0.055 m) 9 times in 10. Was 0.003 (2.9 sd in y: 0.4 % of correct streams failed).
  const GpsStatistics a = gps_statistics(run.log, late, Eigen::Vector2d::Zero());
  EXPECT_NEAR(a.lag_s, 10.0, 0.5);
  EXPECT_NEAR(a.rate_hz, 1.0, 1e-9);
  EXPECT_NEAR(a.white_x_m.sigma_sd, 0.05, 0.0035);  // 3.7 sd
  EXPECT_NEAR(a.white_y_m.sigma_sd, 0.05, 0.0035);  // 3.4 sd
  // Over the same 100: the tether 2.974 m, sd 0.002 m (its fit 0.026 m short, the buoy's
  // catch-up; 0.15 m is a tether 5 % off, 63 sd); the lag 14.81 s, sd 0.013 s (the bound is the
  // L / speed rule's, not a spread); the tether's residual 0.093 m, sd 0.0007 m, at most 0.0945 m
  // (0.1 is 11 sd); the longest lag's structure 0.0070 m^2, sd 0.00014 (0.01 is 22 sd; a slow
  // error adding 0.003 m^2 there, about 0.04 m of sd, reaches it).
  const GpsStatistics b = gps_statistics(run.log, towed, Eigen::Vector2d::Zero());
  EXPECT_NEAR(b.tether_m, 3.0, 0.15);
  EXPECT_NEAR(b.lag_s, 3.0 / 0.2, 2.0);    // a tether of L m lags by about L / speed
  EXPECT_LT(b.tether_residual_m, 0.1);     // 11 sd
  EXPECT_LT(b.structure_m2.back(), 0.01);  // 22 sd: no slow error was added
}

TEST(GpsStatistics, StructureFunctionOfAGaussMarkovError) {
  // With exact navigation, S(k) of the GPS error is the Gauss-Markov one, sigma^2 (1 - e^(-k/tau)).
  const SyntheticRun run = synthetic_run(20000.0);
  std::mt19937 rng(testing::seed(13));
  std::normal_distribution<double> n01(0.0, 1.0);
  const double sigma = 1.0, tau_s = 60.0, phi = std::exp(-1.0 / tau_s);
  Eigen::Vector2d e = sigma * draws_last_first<2>([&] { return n01(rng); });
  std::vector<PositionFix> gps;
  for (std::size_t i = 0; i < run.truth.size(); i += 10) {
    gps.push_back({run.truth[i].t_s, run.truth[i].p_world_m + e});
    e = phi * e +
        sigma * std::sqrt(1.0 - phi * phi) * draws_last_first<2>([&] { return n01(rng); });
  }
  const GpsOptions options;
  const GpsStatistics s = gps_statistics(run.log, gps, Eigen::Vector2d::Zero(), options);
  ASSERT_EQ(s.structure_m2.size(), options.structure_lags_s.size());
  // No tether: the fit's minimum is at 0, or at its first grid point (0.1 m) whence the parabola
  // puts it between (0.054-0.069 m in 3 of 60 seed offsets). Was an exact 0, failing 3 of 20.
  // Not a statistic's spread: the grid's first point bounds where a correct fit can put it.
  EXPECT_LT(s.tether_m, 0.1);
  // S(k)'s relative spread over 60 seed offsets, per lag (1 ... 120 s): 20,000 s hold 330
  // correlation times, fewer independent pairs at the longer lags. Bounds at 4 spreads: the 10
  // lags together fail a correct stream less than 0.001 of the time (Bonferroni). Caught: a
  // correlation time of 50 s for 60 (S(10 s) 18 % high, 10 spreads). Was 15 % at every lag:
  // 2.8 spreads at 120 s, and failed in 1 of 20 offsets.
  const double spread[] = {0.008, 0.008, 0.012, 0.018, 0.028, 0.034, 0.039, 0.041, 0.050, 0.054};
  ASSERT_EQ(std::size(spread), s.structure_m2.size());
  for (std::size_t i = 0; i < s.structure_m2.size(); ++i) {
    const double expected = sigma * sigma * (1.0 - std::exp(-options.structure_lags_s[i] / tau_s));
    EXPECT_NEAR(s.structure_m2[i], expected, 4.0 * spread[i] * expected)
        << "lag " << options.structure_lags_s[i];
  }
}

TEST(Drift, ExactNavigationHasNoDrift) {
  const SyntheticRun run = synthetic_run(3000.0);
  for (const bool ekf : {true, false}) {
    DriftOptions options;
    options.use_ekf = ekf;
    const DriftStatistics s =
        dead_reckoning_drift(run.log, run.truth, Eigen::Vector2d::Zero(), options);
    ASSERT_GE(s.end_error_m.size(), 20u);  // 600 m of path, windows every 25 m
    // Plain integration holds each DVL sample's heading for 0.67 s while turning at up to
    // 3 deg/s: 0.13 m per 100 m of discretisation error.
    EXPECT_LT(s.p90_m, ekf ? 0.1 : 0.15) << (ekf ? "EKF" : "integration");
  }
}

TEST(Drift, AHeadingOffsetDriftsByTheChordOfEachWindow) {
  // On a straight line, a constant 1 deg heading offset rotates each 100 m window's track about
  // its start: the end error is 2 sin(0.5 deg) x 100 m = 1.745 m, exactly for plain integration.
  const SyntheticRun run = synthetic_run(3000.0, 1.0 * kDegToRad, 0.0);
  for (const bool ekf : {false, true}) {
    DriftOptions options;
    options.use_ekf = ekf;
    const DriftStatistics s =
        dead_reckoning_drift(run.log, run.truth, Eigen::Vector2d::Zero(), options);
    ASSERT_GE(s.end_error_m.size(), 20u);
    const double expected_m = 2.0 * std::sin(0.5 * kDegToRad) * 100.0;
    for (const double e : s.end_error_m) {
      EXPECT_NEAR(e, expected_m, ekf ? 0.03 : 0.02) << (ekf ? "EKF" : "integration");
    }
    EXPECT_NEAR(s.mean_m, expected_m, ekf ? 0.03 : 0.02);
  }
}

TEST(HeadingOffset, RecoversAConstantOffset) {
  const SyntheticRun run = synthetic_run(3000.0, 3.0 * kDegToRad);
  const HeadingOffsetStatistics s =
      heading_offset_statistics(run.log, run.truth, Eigen::Vector2d::Zero(), 50.0);
  ASSERT_GE(s.window_offset_deg.size(), 10u);
  EXPECT_NEAR(s.mean_deg, 3.0, 0.05);
  EXPECT_LT(s.sd_deg, 0.1);
}

}  // namespace
}  // namespace msislab
