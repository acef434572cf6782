// The navigation noise statistics of the real St. Pere logs (docs/simulator.md, "Navigation noise
// from the real logs"): printed, and checked against the ranges the documentation states.
#include <gtest/gtest.h>

#include <iostream>

#include "app/navigation_statistics.hpp"
#include "test_support.hpp"

namespace msislab::app {
namespace {

void print(const NavigationStatistics& s) {
  std::cout << "DVL rate " << s.dvl.rate_hz << " Hz; surge sd " << s.dvl.surge_mps.sigma_sd
            << " mad " << s.dvl.surge_mps.sigma_mad << " kurt " << s.dvl.surge_mps.kurtosis
            << "; sway sd " << s.dvl.sway_mps.sigma_sd << " mad " << s.dvl.sway_mps.sigma_mad
            << " kurt " << s.dvl.sway_mps.kurtosis << "\n";
  std::cout << "DVL mixture core " << s.dvl.mixture_mps.core_sigma << " outlier fraction "
            << s.dvl.mixture_mps.outlier_fraction << " outlier sigma "
            << s.dvl.mixture_mps.outlier_sigma << " (" << s.dvl.mixture_mps.iterations << " it)\n";
  const DropoutStatistics& d = s.dropouts;
  std::cout << "dropouts " << d.dropouts << "/" << d.rows << " = " << d.fraction << ", bursts "
            << d.bursts << " mean " << d.mean_burst_rows << " rows; dispersion";
  for (const double v : d.dispersion) std::cout << " " << v;
  std::cout << "\n  GE clear " << d.model.clear_loss_probability << " degraded "
            << d.model.degraded_loss_probability << " fraction " << d.model.degraded_fraction
            << " mean " << d.model.degraded_mean_samples << " rows = " << d.degraded_mean_s
            << " s (ll " << d.model.log_likelihood << ", " << d.model.iterations << " it)\n";
  std::cout << "heading rate " << s.heading.rate_hz << " Hz; sd " << s.heading.noise_deg.sigma_sd
            << " mad " << s.heading.noise_deg.sigma_mad << " kurt " << s.heading.noise_deg.kurtosis
            << "\n";
  if (s.compasses) {
    std::cout << "compasses offset " << s.compasses->offset_deg << " deviation "
              << s.compasses->deviation_amplitude_deg << " residual "
              << s.compasses->residual_sd_deg << " block sd " << s.compasses->block_mean_sd_deg
              << " rw bound " << s.compasses->random_walk_bound_deg_per_sqrt_s << "\n";
  }
  if (s.heading_offset) {
    std::cout << "heading offset mean " << s.heading_offset->mean_deg << " median "
              << s.heading_offset->median_deg << " sd " << s.heading_offset->sd_deg << " se "
              << s.heading_offset->standard_error_deg << " consecutive "
              << s.heading_offset->consecutive_sd_deg << " windows "
              << s.heading_offset->window_offset_deg.size() << "\n";
  }
  if (s.gps) {
    std::cout << "GPS rate " << s.gps->rate_hz << " white x " << s.gps->white_x_m.sigma_sd << "/"
              << s.gps->white_x_m.sigma_mad << " y " << s.gps->white_y_m.sigma_sd << "/"
              << s.gps->white_y_m.sigma_mad << "; lag " << s.gps->lag_s << " s (res "
              << s.gps->lag_residual_m << "), tether " << s.gps->tether_m << " m (res "
              << s.gps->tether_residual_m << ")\n  S(k):";
    for (const double v : s.gps->structure_m2) std::cout << " " << v;
    std::cout << "\n  correlated sigma " << s.gps->correlated_m.sigma << " tau "
              << s.gps->correlated_m.time_s << " misfit " << s.gps->correlated_m.rms_misfit << "\n";
  }
  if (s.drift) {
    std::cout << "drift per 100 m: mean " << s.drift->mean_m << " p90 " << s.drift->p90_m << " ("
              << s.drift->end_error_m.size() << " windows)\n";
  }
  if (s.drift_against_gps) {
    std::cout << "drift per 100 m against GPS: mean " << s.drift_against_gps->mean_m << " p90 "
              << s.drift_against_gps->p90_m << "\n";
  }
}

TEST(NavigationStatisticsStPere, EstimatesFallInTheDocumentedRanges) {
  MSISLAB_REQUIRE_STPERE();
  const NavigationStatistics s = navigation_statistics(load_navigation_data(testing::stpere_dir()));
  print(s);
  // DVL: 0.2 m/s from differences, heavy-tailed (kurtosis of the differences 6.5, not 3).
  EXPECT_NEAR(s.dvl.rate_hz, 1.51, 0.03);
  for (const DifferenceNoise& axis : {s.dvl.surge_mps, s.dvl.sway_mps}) {
    EXPECT_NEAR(axis.sigma_sd, 0.205, 0.01);
    EXPECT_NEAR(axis.sigma_mad, 0.148, 0.01);
    EXPECT_GT(axis.kurtosis, 5.5);
  }
  EXPECT_NEAR(s.dvl.mixture_mps.core_sigma, 0.104, 0.01);
  EXPECT_NEAR(s.dvl.mixture_mps.outlier_fraction, 0.25, 0.05);
  EXPECT_NEAR(s.dvl.mixture_mps.outlier_sigma, 0.37, 0.03);
  // Dropouts: 84 of 5045 rows, clustered over tens of seconds.
  EXPECT_EQ(s.dropouts.dropouts, 84u);
  EXPECT_EQ(s.dropouts.rows, 5045u);
  EXPECT_EQ(s.dropouts.bursts, 79u);
  EXPECT_GT(s.dropouts.dispersion[1], 1.5);
  EXPECT_GT(s.dropouts.dispersion[2], 2.5);
  EXPECT_NEAR(s.dropouts.model.degraded_loss_probability, 0.07, 0.02);
  EXPECT_NEAR(s.dropouts.model.degraded_fraction, 0.2, 0.05);
  EXPECT_NEAR(s.dropouts.degraded_mean_s, 28.0, 8.0);
  EXPECT_LT(s.dropouts.model.clear_loss_probability, 0.008);
  // Heading: 0.04 deg at 10 Hz; the two compasses agree to 0.4 deg over 200 s blocks.
  EXPECT_NEAR(s.heading.rate_hz, 10.0, 0.01);
  EXPECT_NEAR(s.heading.noise_deg.sigma_sd, 0.037, 0.005);
  EXPECT_NEAR(s.heading.noise_deg.sigma_mad, 0.047, 0.005);
  ASSERT_TRUE(s.compasses);
  EXPECT_NEAR(s.compasses->offset_deg, -61.5, 1.0);
  EXPECT_NEAR(s.compasses->deviation_amplitude_deg, 5.3, 0.5);
  EXPECT_LT(s.compasses->random_walk_bound_deg_per_sqrt_s, 0.025);
  ASSERT_TRUE(s.heading_offset);
  EXPECT_NEAR(s.heading_offset->mean_deg, -2.1, 1.0);
  EXPECT_NEAR(s.heading_offset->sd_deg, 3.8, 1.0);
  // GPS: smooth (white 0.04-0.06 m), no measurable lag, a ~0.7 m error correlated over ~90 s.
  ASSERT_TRUE(s.gps);
  EXPECT_NEAR(s.gps->white_x_m.sigma_sd, 0.043, 0.01);
  EXPECT_NEAR(s.gps->white_y_m.sigma_sd, 0.058, 0.01);
  EXPECT_NEAR(s.gps->lag_s, 0.0, 1.5);
  EXPECT_LT(s.gps->tether_m, 0.5);
  EXPECT_NEAR(s.gps->correlated_m.sigma, 0.7, 0.2);
  EXPECT_NEAR(s.gps->correlated_m.time_s, 90.0, 40.0);
  // Dead reckoning (EKF) against GPS per 100 m of path.
  ASSERT_TRUE(s.drift);
  EXPECT_GE(s.drift->end_error_m.size(), 20u);
  EXPECT_NEAR(s.drift->mean_m, 4.3, 0.5);
  EXPECT_NEAR(s.drift->p90_m, 7.2, 0.8);
  EXPECT_FALSE(s.drift_against_gps);  // the GPS is the truth here
}

}  // namespace
}  // namespace msislab::app
