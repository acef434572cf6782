// calibration.yaml and the SLAM config file (--config): YAML <-> plain structs, strictly
// (docs/formats.md lists every key).
#pragma once

#include <string>

#include "geometry/calibration.hpp"
#include "slam/slam_config.hpp"

namespace msislab::io {

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

/// Writes the config's dead_reckoning section (every key; the other sections are left at their
/// defaults by their absence), atomically: what an external method is given as {config} when no
/// --config was (docs/formats.md). read_slam_config() reads the same dead-reckoning values back.
void write_dead_reckoning_config(const std::string& path, const DeadReckoningConfig& config);

}  // namespace msislab::io
