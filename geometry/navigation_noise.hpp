// The navigation sensors' errors as the dead reckoning models them: the plain struct behind a
// simulated dataset's navigation_noise.yaml (docs/formats.md). Its names and units are the SLAM
// config's dead_reckoning keys, so a run fed a simulated dataset can take the noise the dataset
// was made with (settings::slam_config_for_dataset).
#pragma once

namespace msislab {

struct NavigationNoise {
  double dvl_sigma_mps = 0.0;                     ///< DVL white noise per axis, m/s (its sd)
  double heading_sigma_deg = 0.0;                 ///< heading white noise, deg
  double heading_bias_walk_deg_per_sqrt_s = 0.0;  ///< the heading bias's random-walk density
  double heading_bias_sigma_deg = 0.0;            ///< the bias's size at the start, deg
  double dvl_scale_sigma = 0.0;  ///< the DVL scale error calibration.yaml does not state
};

}  // namespace msislab
