// The navigation noise statistics of the real St. Pere logs (docs/simulator.md, "Navigation noise
// from the real logs"): printed, and checked against the ranges the documentation states.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <iostream>

#include "dataset/navigation_data.hpp"
#include "io/mesh_io.hpp"
#include "settings/scenario_yaml.hpp"
#include "sim/navigation_sensors.hpp"
#include "sim/vehicle.hpp"
#include "test_support.hpp"

namespace msislab::dataset {
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
              << s.compasses->deviation_amplitude_deg << " (cos " << s.compasses->deviation_cos_deg
              << ", sin " << s.compasses->deviation_sin_deg << ") residual "
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
    std::cout << "\n";
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

  // Dead reckoning (EKF) against GPS per 100 m of path.
  ASSERT_TRUE(s.drift);
  EXPECT_GE(s.drift->end_error_m.size(), 20u);
  EXPECT_NEAR(s.drift->mean_m, 4.3, 0.5);
  EXPECT_NEAR(s.drift->p90_m, 7.2, 0.8);
  EXPECT_FALSE(s.drift_against_gps);  // the GPS is the truth here
}

/// The navigation sensors of a scenario (no sonar) as a dataset would hold them: through the
/// scenario's calibration, truth at 10 Hz.
NavigationData simulate_navigation(const sim::Scenario& scenario, const sim::Scene& scene,
                                   std::uint64_t seed) {
  const sim::VehicleTrajectory truth = sim::follow_path(scenario.vehicle);
  const Calibration calibration = sim::calibration_of(scenario);
  NavigationData data;
  for (const sim::DvlSample& s :
       sim::simulate_dvl(truth, scenario.dvl, scene, scenario.vehicle.depth_m, seed)) {
    data.dvl_rows.push_back({s.t_s, s.bottom_lock, std::nullopt});
    if (!s.bottom_lock) {
      ++data.navigation.dvl_rows_without_bottom_lock;
      continue;
    }
    data.navigation.dvl.push_back({s.t_s, R_vehicle_dvl(calibration.dvl) * s.v_dvl_mps});
  }
  for (const sim::MruSample& s : sim::simulate_mru(truth, scenario.mru, seed)) {
    data.navigation.heading.push_back(
        {s.t_s, vehicle_yaw_from_mru(s.yaw_mru_deg, calibration.mru)});
  }
  for (const sim::GpsFix& f : sim::simulate_gps(truth, scenario.gps, seed)) {
    data.gps.push_back({f.t_s, f.p_world_m});
  }
  for (std::size_t i = 0; i < truth.samples().size(); i += 10) {
    data.truth.push_back({truth.samples()[i].t_s, truth.samples()[i].pose.translation()});
  }
  data.truth_kind = "simulation";
  data.p_vehicle_dvl_m = {calibration.dvl.x_m, calibration.dvl.y_m};
  return data;
}

/// The statistics compared between the real and the simulated logs (docs/simulator.md).
struct Compared {
  const char* name;
  double (*of)(const NavigationStatistics&);
  /// Relative difference allowed between the real value and the replica's expected value (the
  /// seeds' mean, within its sampling error); 0: printed, not checked.
  double tolerance;
};
const std::vector<Compared> kCompared = {
    {"DVL surge sigma, sd of differences (m/s)",
     [](const NavigationStatistics& s) { return s.dvl.surge_mps.sigma_sd; }, 0.1},
    {"DVL sway sigma, sd of differences (m/s)",
     [](const NavigationStatistics& s) { return s.dvl.sway_mps.sigma_sd; }, 0.1},
    {"DVL surge sigma, MAD of differences (m/s)",
     [](const NavigationStatistics& s) { return s.dvl.surge_mps.sigma_mad; }, 0.1},
    {"DVL sway sigma, MAD of differences (m/s)",
     [](const NavigationStatistics& s) { return s.dvl.sway_mps.sigma_mad; }, 0.1},
    {"DVL surge kurtosis of differences",
     [](const NavigationStatistics& s) { return s.dvl.surge_mps.kurtosis; }, 0.25},
    {"DVL dropout fraction", [](const NavigationStatistics& s) { return s.dropouts.fraction; },
     0.2},
    {"DVL dropout dispersion, 5 rows",
     [](const NavigationStatistics& s) { return s.dropouts.dispersion[0]; }, 0.2},
    {"DVL dropout dispersion, 30 rows",
     [](const NavigationStatistics& s) { return s.dropouts.dispersion[1]; }, 0.2},
    {"DVL dropout dispersion, 300 rows",
     [](const NavigationStatistics& s) { return s.dropouts.dispersion[2]; }, 0.3},
    {"heading sigma, sd of 2nd differences (deg)",
     [](const NavigationStatistics& s) { return s.heading.noise_deg.sigma_sd; }, 0.2},
    {"heading sigma, MAD of 2nd differences (deg)",
     [](const NavigationStatistics& s) { return s.heading.noise_deg.sigma_mad; }, 0.2},
    {"heading offset spread over 50 m windows (deg)",
     [](const NavigationStatistics& s) { return s.heading_offset->sd_deg; }, 0.3},
    {"GPS sigma, sd of 2nd differences (m)",
     [](const NavigationStatistics& s) {
       return 0.5 * (s.gps->white_x_m.sigma_sd + s.gps->white_y_m.sigma_sd);
     },
     0.2},
    {"GPS - DR residual over 60 s windows (m)",
     [](const NavigationStatistics& s) { return s.gps->lag_residual_m; }, 0.1},
    {"GPS - DR structure function at 10 s (m^2)",
     [](const NavigationStatistics& s) { return s.gps->structure_m2[3]; }, 0.2},
    {"GPS - DR structure function at 60 s (m^2)",
     [](const NavigationStatistics& s) { return s.gps->structure_m2[7]; }, 0.2},
    {"GPS - DR structure function at 120 s (m^2)",
     [](const NavigationStatistics& s) { return s.gps->structure_m2[9]; }, 0.2},
    {"DR drift per 100 m vs truth, mean (m)",
     [](const NavigationStatistics& s) { return s.drift->mean_m; }, 0.2},
    {"DR drift per 100 m vs truth, p90 (m)",
     [](const NavigationStatistics& s) { return s.drift->p90_m; }, 0.2},
    {"DR drift per 100 m vs GPS, mean (m)",
     [](const NavigationStatistics& s) {
       return s.drift_against_gps ? s.drift_against_gps->mean_m : s.drift->mean_m;
     },
     0.2},
    // Printed for the record: not modelled (the offset) or a fit that one run cannot pin down.
    {"heading offset, mean over 50 m windows (deg)",
     [](const NavigationStatistics& s) { return s.heading_offset->mean_deg; }, 0.0},
    {"GPS lag behind the dead reckoning (s)",
     [](const NavigationStatistics& s) { return s.gps->lag_s; }, 0.0},
    {"GPS taut-tether length (m)", [](const NavigationStatistics& s) { return s.gps->tether_m; },
     0.0},
    {"DVL mixture: core sigma (m/s)",
     [](const NavigationStatistics& s) { return s.dvl.mixture_mps.core_sigma; }, 0.0},
    {"DVL mixture: outlier fraction",
     [](const NavigationStatistics& s) { return s.dvl.mixture_mps.outlier_fraction; }, 0.0},
    {"DVL mixture: outlier sigma (m/s)",
     [](const NavigationStatistics& s) { return s.dvl.mixture_mps.outlier_sigma; }, 0.0},
    {"dropouts: degraded-state loss probability",
     [](const NavigationStatistics& s) { return s.dropouts.model.degraded_loss_probability; }, 0.0},
    {"dropouts: degraded fraction",
     [](const NavigationStatistics& s) { return s.dropouts.model.degraded_fraction; }, 0.0},
    {"dropouts: degraded period (s)",
     [](const NavigationStatistics& s) { return s.dropouts.degraded_mean_s; }, 0.0},
};

/// The shipped replica scenario with its scene, loaded once.
struct Replica {
  sim::Scenario scenario =
      settings::read_scenario(std::string(MSISLAB_SOURCE_DIR) + "/scenarios/stpere_replica.yaml");
  sim::Scene scene{io::read_mesh(scenario.scene.mesh_path,
                                 {scenario.scene.default_material, scenario.scene.group_materials}),
                   scenario.scene.surface};
};

TEST(NavigationStatisticsStPere, ReplicaMatchesTheRealStatistics) {
  // The replica's navigation with the default noise models, seeds 42 to 53, against the real
  // logs: every compared statistic's expected value under the replica lies within its relative
  // tolerance (20% for most) of the real value.
  MSISLAB_REQUIRE_STPERE();
  const NavigationStatistics real =
      navigation_statistics(load_navigation_data(testing::stpere_dir()));
  const Replica replica;
  std::vector<NavigationStatistics> runs;
  for (std::uint64_t seed = 42; seed < 54; ++seed) {
    runs.push_back(navigation_statistics(simulate_navigation(
        replica.scenario, replica.scene, testing::seed(static_cast<unsigned>(seed)))));
  }
  const double n = static_cast<double>(runs.size());
  std::cout << "| statistic | real | simulated, seed 42 | simulated, 12 seeds: mean (sd) | "
               "standard error of the mean | allowed difference |\n";
  for (const Compared& c : kCompared) {
    double mean = 0.0, var = 0.0;
    for (const NavigationStatistics& r : runs) mean += c.of(r) / n;
    for (const NavigationStatistics& r : runs) var += std::pow(c.of(r) - mean, 2) / (n - 1.0);
    // The seeds' mean estimates the replica's expected value with standard error sd / sqrt(n)
    // (sd: the sample standard deviation over the n = 12 runs). The claim is about the expected
    // value, so the allowed difference is the relative tolerance plus 3 standard errors of that
    // mean (99.7 % two-sided, were the mean normal): the seeds' own sampling error, not one run's
    // spread. The real value is a single run of the real process: its own run-to-run spread is
    // not modelled here and must fit within the relative tolerance. Never wider than the bound
    // this replaced (the larger of the relative tolerance and two standard deviations of one
    // run), which was about 3.5 standard errors wide where one run's spread set it.
    const double standard_error = std::sqrt(var / n);
    const double relative = c.tolerance * std::abs(c.of(real));
    const double allowed =
        std::min(relative + 3.0 * standard_error, std::max(relative, 2.0 * std::sqrt(var)));
    std::cout << "| " << c.name << " | " << c.of(real) << " | " << c.of(runs.front()) << " | "
              << mean << " (" << std::sqrt(var) << ") | " << standard_error << " | "
              << (c.tolerance > 0.0 ? allowed : 0.0) << " |\n";
    if (c.tolerance > 0.0) {
      EXPECT_NEAR(mean, c.of(real), allowed) << c.name;
    }
  }
}

/// The simulated GPS error is calibrated by matching, on average over simulated runs, the GPS
/// statistics of the real logs: the structure function, the 60 s residual and the second
/// differences (docs/simulator.md). Slow (minutes): run with --gtest_also_run_disabled_tests.
TEST(NavigationStatisticsStPere, OneReplicaSeedGivesEveryComparedStatistic) {
  // ReplicaMatchesTheRealStatistics' code on one seed: the sanitizer suite runs this instead of
  // its 12 seeds (125 s under AddressSanitizer; docs/reliability.md). Every statistic it checks
  // is estimated and finite, the GPS's, the heading offset's and the drift's included.
  const Replica replica;
  const NavigationStatistics run =
      navigation_statistics(simulate_navigation(replica.scenario, replica.scene, 42));
  ASSERT_TRUE(run.gps.has_value());
  ASSERT_TRUE(run.heading_offset.has_value());
  ASSERT_TRUE(run.drift.has_value());
  for (const Compared& c : kCompared) {
    if (c.tolerance > 0.0) {
      EXPECT_TRUE(std::isfinite(c.of(run))) << c.name;
    }
  }
}

TEST(NavigationStatisticsStPere, DISABLED_CalibrateTheGpsError) {
  MSISLAB_REQUIRE_STPERE();
  const NavigationStatistics real =
      navigation_statistics(load_navigation_data(testing::stpere_dir()));
  Replica replica;
  const auto gps_sigma = [](const NavigationStatistics& s) {
    return 0.5 * (s.gps->white_x_m.sigma_sd + s.gps->white_y_m.sigma_sd);
  };
  for (const double sigma_m : {0.0, 0.7, 0.85, 1.0, 1.2, 1.4}) {
    for (const double tau_s : {90.0, 200.0, 300.0, 500.0, 800.0}) {
      if (sigma_m == 0.0 && tau_s != 90.0) continue;  // no error: tau does not matter
      replica.scenario.gps.correlated_sigma_m = sigma_m;
      replica.scenario.gps.correlation_time_s = tau_s;
      // The mismatch: squared log ratios of S(k) at every lag, the residual and the sigma.
      std::vector<double> s(real.gps->structure_m2.size(), 0.0);
      double residual = 0.0, sigma = 0.0;
      for (std::uint64_t seed = 1; seed <= 12; ++seed) {
        const NavigationStatistics r =
            navigation_statistics(simulate_navigation(replica.scenario, replica.scene, seed));
        for (std::size_t k = 0; k < s.size(); ++k) s[k] += r.gps->structure_m2[k] / 12.0;
        residual += r.gps->lag_residual_m / 12.0;
        sigma += gps_sigma(r) / 12.0;
      }
      double mismatch = std::pow(std::log(residual / real.gps->lag_residual_m), 2) +
                        std::pow(std::log(sigma / gps_sigma(real)), 2);
      for (std::size_t k = 0; k < s.size(); ++k) {
        mismatch += std::pow(std::log(s[k] / real.gps->structure_m2[k]), 2);
      }
      std::cout << "sigma " << sigma_m << " m, tau " << tau_s << " s: mismatch " << mismatch
                << std::endl;
    }
  }
}

}  // namespace
}  // namespace msislab::dataset
