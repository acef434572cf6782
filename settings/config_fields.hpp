// Readers of the YAML sections shared by calibration.yaml, the SLAM config and scenario files.
// Internal to io/. Each reads the keys it knows into the struct (absent keys keep their values) and
// leaves finish() to the caller, who may read more keys from the same mapping.
#pragma once

#include <string>
#include <vector>

#include "eval/evaluation.hpp"
#include "geometry/calibration.hpp"
#include "io/yaml_fields.hpp"
#include "slam/slam_config.hpp"

namespace msislab::settings {

/// Fails naming the key unless value > 0.
void require_positive(io::YamlMap& map, const std::string& key, double value);

/// Reads an integer into value if present; fails naming the key unless min <= value <= max.
void read_count(io::YamlMap& map, const std::string& key, int& value, int min, int max);

/// line_radius_m, line_min_points, line_max_eigen_ratio (the matcher's lines and the footprint's).
void read_line_normals(io::YamlMap& map, LineNormalConfig& line);

void read_mru_mount(io::YamlMap& map, MruMount& mount);  ///< yaw_offset_deg
void read_dvl_mount(io::YamlMap& map, DvlMount& mount);  ///< yaw_deg, x_m, y_m
void read_sonar_mount(io::YamlMap& map,
                      SonarMount& mount);  ///< x_m, y_m, z_m, bearing_offset_deg, bearing_sign
void read_local_frame(io::YamlMap& map,
                      LocalFrame& frame);  ///< origin_latitude_deg, origin_longitude_deg

/// calibration.yaml's sections (mru, dvl, sonar, frame) of `root` into c; absent keys keep their
/// values. Calls finish() on each section, not on root.
void read_calibration_sections(io::YamlMap& root, Calibration& c);

/// A SLAM config's keys over `base` (absent keys keep base's values); `path` names the file in
/// errors. A null node reads as an empty file.
SlamConfig slam_config_of(const YAML::Node& node, const std::string& path, const SlamConfig& base);

/// `name: [begin_s, end_s]` entries in file order; calls finish() on the mapping.
std::vector<TimeSegment> read_segments(io::YamlMap map);

}  // namespace msislab::settings
