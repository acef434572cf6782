// calibration.yaml and the SLAM config file (--config): YAML <-> plain structs, strictly
// (docs/formats.md lists every key).
#pragma once

#include <string>

#include "slam/calibration.hpp"
#include "slam/slam_config.hpp"

namespace msislab::io {

/// Reads calibration.yaml; absent keys keep the St. Pere defaults.
Calibration read_calibration(const std::string& path);
/// Writes every calibration key, atomically; read_calibration() reads it back exactly.
void write_calibration(const std::string& path, const Calibration& calibration);

/// Reads a SLAM config file; absent keys keep their defaults.
SlamConfig read_slam_config(const std::string& path);

}  // namespace msislab::io
