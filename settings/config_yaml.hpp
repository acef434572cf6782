// calibration.yaml and the SLAM config file (--config): YAML <-> plain structs, strictly
// (docs/formats.md lists every key).
#pragma once

#include <optional>
#include <string>

#include "geometry/calibration.hpp"
#include "geometry/navigation_noise.hpp"
#include "slam/slam_config.hpp"

namespace msislab::settings {

/// Reads calibration.yaml; absent keys keep the St. Pere defaults.
Calibration read_calibration(const std::string& path);
/// Writes every calibration key, atomically, with 17 significant digits; read_calibration()
/// reads it back exactly except the sonar's bearing offset, stored in degrees.
void write_calibration(const std::string& path, const Calibration& calibration);
/// What read_calibration() gives back for a file write_calibration() wrote: a dataset held in
/// memory carries this, so its methods see the bits a dataset directory would give them.
Calibration calibration_as_stored(const Calibration& calibration);

/// Reads a SLAM config file; absent keys keep their defaults.
SlamConfig read_slam_config(const std::string& path);
/// The same from a config's text; `name` stands for the file in errors.
SlamConfig read_slam_config_text(const std::string& text, const std::string& name);

/// A simulated dataset's navigation_noise.yaml (geometry/navigation_noise.hpp): strict, every
/// value >= 0, absent keys 0.
NavigationNoise read_navigation_noise(const std::string& path);
/// Writes it, atomically, every key.
void write_navigation_noise(const std::string& path, const NavigationNoise& noise);
/// What read_navigation_noise() gives back for a file write_navigation_noise() wrote.
NavigationNoise navigation_noise_as_stored(const NavigationNoise& noise);

/// The config a run on a dataset uses and where its noise came from.
struct DatasetConfig {
  SlamConfig config;
  std::string noise_note;  ///< which of the dataset's noise values it took; "" when none
};
/// The config file's keys (config_path empty: none) over the dataset's navigation noise (each of
/// its dead_reckoning keys the file does not set; a white-noise sigma of 0 is not taken, a filter
/// needs one above 0) over the defaults. noise_source names the noise in the note.
DatasetConfig slam_config_for_dataset(const std::string& config_path,
                                      const std::optional<NavigationNoise>& noise,
                                      const std::string& noise_source);

}  // namespace msislab::settings
