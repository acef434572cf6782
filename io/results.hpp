// The files of a result directory (docs/formats.md): trajectory.tum and metrics.json.
#pragma once

#include <string>
#include <vector>

#include "slam/evaluation.hpp"

namespace msislab::io {

/// Writes a trajectory as TUM (z = -depth_m, planar yaw as a quaternion), atomically.
void write_trajectory_tum(const std::string& path, const std::vector<StampedPose>& trajectory,
                          double depth_m);

/// Writes metrics.json atomically. `dataset_dir` is recorded so `msislab eval` can find the truth.
void write_metrics_json(const std::string& path, const RunMetrics& metrics,
                        const std::string& dataset_dir);

/// JSON text of a number: shortest round-trip form, null when not finite.
std::string json_number(double value);
/// JSON string literal with escapes.
std::string json_string(const std::string& text);

}  // namespace msislab::io
