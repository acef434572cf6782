// `msislab scans DATASET_DIR --out DIR [--config SLAM.yaml]`: the sonar front end on its own:
// beams segmented, revolutions built into motion-compensated scans placed by dead reckoning,
// written with their figures (docs/front_end.md).
#pragma once

#include <optional>
#include <string>

namespace msislab::app {

struct ScansOptions {
  std::string dataset_dir;
  std::string out_dir;
  std::string config_path;  ///< empty: defaults
  int figure_scan = -1;     ///< scan drawn before/after compensation; -1: the middle one
  bool force = false;       ///< replace a folder msislab did not write
};

struct ScansSummary {
  std::string source;  ///< "IS log" or "detections"
  std::size_t beams = 0;
  std::size_t beams_with_readings = 0;
  std::size_t scans = 0;
  std::size_t points = 0;
  /// Simulated data: mean distance between a reading placed through the scan (true centre pose
  /// (+) scan point) and where it really was (true pose at its beam (+) its vehicle-frame point),
  /// with and without motion compensation.
  std::optional<double> compensated_error_m;
  std::optional<double> uncompensated_error_m;
};

ScansSummary build_scans_command(const ScansOptions& options);

}  // namespace msislab::app
