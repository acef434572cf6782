// The SLAM config an external method is given as {config} (docs/formats.md, "Methods files"):
// the values the run resolved, written where the program can read them.
#pragma once

#include <string>

#include "slam/dead_reckoning.hpp"

namespace msislab::settings {

/// Writes the config's dead_reckoning section (every key; the other sections are left at their
/// defaults by their absence), atomically: what an external method is given as {config} when no
/// --config was. read_slam_config() reads the same dead-reckoning values back.
void write_dead_reckoning_config(const std::string& path, const DeadReckoningConfig& config);

/// Writes the config file at config_path with its dead_reckoning section set to `resolved` (every
/// key, the values the run took from the dataset's navigation_noise.yaml among them) and
/// `navigation_noise: config`, atomically: what an external method is given as {config} when the
/// --config it names says `navigation_noise: dataset`, so the program reads the figures msislab's
/// own methods use. Every other key as the file has it (its comments are not kept).
/// read_slam_config() reads the resolved values back.
void write_resolved_config(const std::string& path, const std::string& config_path,
                           const DeadReckoningConfig& resolved);

}  // namespace msislab::settings
