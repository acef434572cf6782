// Navigation noise statistics of a dataset, real or simulated, from its own logs (docs/simulator.md
// "Navigation noise from the real logs"): DVL noise, dropouts, MRU heading noise and offset, the
// GPS buoy's lag and error, and dead-reckoning drift per distance travelled. Pure functions of
// already-loaded data returning plain structs; io/navigation_data reads the logs.
#pragma once

#include <Eigen/Core>
#include <optional>
#include <string>
#include <vector>

#include "eval/evaluation.hpp"
#include "eval/noise_model_fit.hpp"
#include "slam/dead_reckoning.hpp"
#include "slam/navigation.hpp"

namespace msislab {

/// White-noise level of a sampled signal from its n-th differences. For white noise of standard
/// deviation sigma on a signal that is smooth at the sample rate, the first differences have
/// variance 2 sigma^2 and the second differences 6 sigma^2.
struct DifferenceNoise {
  double sigma_sd = 0.0;   ///< standard deviation of the differences / sqrt(2 or 6)
  double sigma_mad = 0.0;  ///< 1.4826 x median absolute deviation / sqrt(2 or 6): robust
  double kurtosis = 0.0;   ///< of the differences; 3 for Gaussian noise
  std::size_t count = 0;   ///< differences used
};

/// order 1 or 2: the noise from first or second differences of values (needs >= order + 2).
DifferenceNoise difference_noise(const std::vector<double>& values, int order);

/// One row of the DVL log, whatever its bottom lock, with the DVL's own compass.
struct DvlRow {
  double t_s = 0.0;
  bool bottom_lock = false;
  std::optional<double> compass_yaw_rad;  ///< vehicle-convention yaw; none when not logged
};

/// Everything the statistics read from one dataset.
struct NavigationData {
  NavigationLog navigation;        ///< DVL with bottom lock and MRU heading, vehicle frame
  std::vector<DvlRow> dvl_rows;    ///< every DVL row, in time order
  std::vector<PositionFix> gps;    ///< the GPS log (empty when the dataset has none)
  std::vector<PositionFix> truth;  ///< simulation truth, else the GPS
  std::string truth_kind;          ///< "simulation", "gps" or empty
  Eigen::Vector2d p_vehicle_dvl_m = Eigen::Vector2d::Zero();  ///< DVL lever arm
};

struct DvlNoiseStatistics {
  double rate_hz = 0.0;  ///< 1 / median interval between consecutive DVL rows
  /// First differences of consecutive bottom-lock samples (no dropout between), vehicle axes.
  DifferenceNoise surge_mps, sway_mps;
  ContaminatedNormal mixture_mps;  ///< heavy tails: fit to the same 2-D differences
};
DvlNoiseStatistics dvl_noise_statistics(const std::vector<DvlVelocity>& dvl);

struct DropoutStatistics {
  std::size_t rows = 0;
  std::size_t dropouts = 0;    ///< rows without bottom lock
  double fraction = 0.0;       ///< dropouts / rows
  std::size_t bursts = 0;      ///< runs of consecutive dropouts
  double mean_burst_rows = 0;  ///< dropouts / bursts
  /// Dispersion index (variance / mean) of the dropout count in consecutive blocks of
  /// kDispersionBlocks[i] rows: 1 - fraction for independent dropouts, larger when clustered.
  std::vector<double> dispersion;
  GilbertElliott model;          ///< bursty-loss fit, per row
  double degraded_mean_s = 0.0;  ///< model.degraded_mean_samples / rate
};
inline const std::vector<int> kDispersionBlocks = {5, 30, 300};
DropoutStatistics dropout_statistics(const std::vector<DvlRow>& rows, double rate_hz);

struct HeadingNoiseStatistics {
  double rate_hz = 0.0;
  DifferenceNoise noise_deg;  ///< second differences of the wrapped heading (turns cancel)
  /// How much the vehicle turns between two scans: the median |heading change| over one sonar
  /// revolution (13.8 s), every revolution's length along the log, deg.
  double turn_per_revolution_deg = 0.0;
};
HeadingNoiseStatistics heading_noise_statistics(const std::vector<HeadingReading>& heading);

/// MRU heading against the DVL's own compass: their difference fitted as
/// offset + a cos(yaw) + b sin(yaw) (a one-cycle deviation curve of either compass), and what is
/// left over time. Both compasses see the same magnetic field, so this bounds their relative
/// drift, not a common one.
struct CompassComparison {
  double offset_deg = 0.0;
  double deviation_amplitude_deg = 0.0;  ///< sqrt(a^2 + b^2)
  double deviation_cos_deg = 0.0;        ///< a
  double deviation_sin_deg = 0.0;        ///< b
  double residual_sd_deg = 0.0;
  double block_mean_sd_deg = 0.0;  ///< sd of the residual's means over blocks of kCompassBlock_s
  /// A heading bias random walk of density q, seen over a span T, has an sd of about q sqrt(T / 6)
  /// around its mean: block_mean_sd / sqrt(T / 6) bounds the MRU's own random walk density.
  double random_walk_bound_deg_per_sqrt_s = 0.0;
};
inline constexpr double kCompassBlock_s = 200.0;
/// nullopt when the DVL rows carry no compass (simulated data).
std::optional<CompassComparison> compare_compasses(const std::vector<HeadingReading>& heading,
                                                   const std::vector<DvlRow>& rows);

/// Dead reckoning against truth over windows of path length. A window starts at a truth sample
/// and ends at the first one `window_m` further along the path; the dead reckoning restarts at
/// the truth position (heading from the MRU) at each window start. Path length counts truth
/// steps of at least `path_step_m`, so GPS jitter does not add length.
struct DriftOptions {
  double window_m = 100.0;   ///< path length per window, m
  double stride_m = 25.0;    ///< path between window starts (windows overlap when < window), m
  double path_step_m = 1.0;  ///< path measured between truth points this far apart, m
  bool use_ekf = true;       ///< slam/dead_reckoning EKF; false: plain integration
  DeadReckoningConfig ekf;   ///< the EKF's noise settings
};
struct DriftStatistics {
  std::vector<double> end_error_m;  ///< per window
  double mean_m = 0.0;
  double p90_m = 0.0;
};
DriftStatistics dead_reckoning_drift(const NavigationLog& navigation,
                                     const std::vector<PositionFix>& truth,
                                     const Eigen::Vector2d& p_vehicle_dvl_m,
                                     const DriftOptions& options);

/// The constant heading offset of the DVL-integrated track against truth: per window of path
/// (non-overlapping), the rotation that best aligns the centred dead-reckoned positions with the
/// centred truth positions, sign flipped (so it is what the MRU heading plus the DVL mount add).
struct HeadingOffsetStatistics {
  std::vector<double> window_offset_deg;
  double mean_deg = 0.0;
  double median_deg = 0.0;
  double sd_deg = 0.0;
  double standard_error_deg = 0.0;  ///< sd / sqrt(windows)
  double consecutive_sd_deg = 0.0;  ///< sd of differences of neighbours / sqrt(2)
};
HeadingOffsetStatistics heading_offset_statistics(const NavigationLog& navigation,
                                                  const std::vector<PositionFix>& truth,
                                                  const Eigen::Vector2d& p_vehicle_dvl_m,
                                                  double window_m);

struct GpsOptions {
  double window_s = 60.0;  ///< windows whose mean offset is removed before the residual
  double max_lag_s = 60.0;
  double max_tether_m = 15.0;
  /// Removed from the MRU heading before dead reckoning (heading_offset_statistics' mean), so a
  /// constant heading or DVL-mount offset is not mistaken for slow GPS error.
  double heading_offset_deg = 0.0;
  /// Lags of the structure function, s.
  std::vector<double> structure_lags_s = {1, 2, 5, 10, 20, 30, 45, 60, 90, 120};
};
struct GpsStatistics {
  double rate_hz = 0.0;
  DifferenceNoise white_x_m, white_y_m;  ///< second differences of the fixes
  /// Time shift of the GPS behind the dead-reckoned track that minimises the windowed residual
  /// (positive: the GPS lags the vehicle), with that residual per axis.
  double lag_s = 0.0;
  double lag_residual_m = 0.0;
  /// The same for a buoy towed on a taut tether (sim/navigation_sensors): the horizontal length.
  double tether_m = 0.0;
  double tether_residual_m = 0.0;
  /// Structure function S(k) = E[(e(t + k) - e(t))^2] / 2 per axis (mean of x and y) of
  /// e = GPS - dead reckoning (tether applied), at GpsOptions::structure_lags_s: the GPS's own
  /// slow error plus the dead reckoning's drift, which one run cannot separate (docs/simulator.md
  /// calibrates the simulated GPS error by matching it).
  std::vector<double> structure_m2;
};
/// Needs at least one window of fixes after the first heading.
GpsStatistics gps_statistics(const NavigationLog& navigation, const std::vector<PositionFix>& gps,
                             const Eigen::Vector2d& p_vehicle_dvl_m,
                             const GpsOptions& options = {});

/// The simulator's towed buoy (sim::drag_buoy) behind a vehicle track: it stays put while within
/// L of the vehicle and is dragged along the line to it otherwise.
std::vector<PositionFix> towed_buoy(const std::vector<PositionFix>& vehicle, double tether_m);

struct NavigationStatistics {
  DvlNoiseStatistics dvl;
  DropoutStatistics dropouts;
  HeadingNoiseStatistics heading;
  std::optional<CompassComparison> compasses;
  std::optional<HeadingOffsetStatistics> heading_offset;  ///< against the GPS, else truth
  std::optional<GpsStatistics> gps;                       ///< with a GPS log
  std::optional<DriftStatistics> drift;                   ///< against truth
  std::optional<DriftStatistics> drift_against_gps;       ///< simulated data: against its GPS
};
NavigationStatistics navigation_statistics(const NavigationData& data);

}  // namespace msislab
