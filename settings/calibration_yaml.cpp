// calibration.yaml (docs/formats.md): its sections read into the Calibration struct (shared with
// a scenario's stated_calibration), written back with every key at 17 significant digits.
#include <cmath>
#include <iomanip>
#include <sstream>

#include "geometry/angles.hpp"
#include "io/atomic_file.hpp"
#include "settings/config_fields.hpp"
#include "settings/config_yaml.hpp"

namespace msislab::settings {

void read_calibration_sections(io::YamlMap& root, Calibration& c) {
  io::YamlMap mru = root.map("mru");
  read_mru_mount(mru, c.mru);
  // The compass deviation is calibration, not mount: a scenario sets its MRU's own.
  mru.number("deviation_cos_deg", c.mru.deviation_cos_deg);
  mru.number("deviation_sin_deg", c.mru.deviation_sin_deg);
  if (std::hypot(c.mru.deviation_cos_deg, c.mru.deviation_sin_deg) >= 45.0) {
    mru.fail("deviation_cos_deg", "the deviation's amplitude must be under 45 deg");
  }
  mru.finish();
  // The scale factors are calibration, not mount: a scenario sets its sensors' own (the DVL's
  // scale_factor, the sonar's sound speeds).
  io::YamlMap dvl = root.map("dvl");
  read_dvl_mount(dvl, c.dvl);
  dvl.number("scale_factor", c.dvl.scale_factor);
  if (!(c.dvl.scale_factor >= 0.5 && c.dvl.scale_factor <= 2.0)) {
    dvl.fail("scale_factor", "must be in [0.5, 2]");
  }
  dvl.finish();
  io::YamlMap sonar = root.map("sonar");
  read_sonar_mount(sonar, c.sonar);
  sonar.number("range_scale", c.sonar.range_scale);
  if (!(c.sonar.range_scale >= 0.5 && c.sonar.range_scale <= 2.0)) {
    sonar.fail("range_scale", "must be in [0.5, 2]");
  }
  sonar.finish();
  io::YamlMap frame = root.map("frame");
  read_local_frame(frame, c.frame);
  frame.finish();
}

namespace {
Calibration calibration_from_yaml(const YAML::Node& node, const std::string& name) {
  io::YamlMap root(node, name, "");
  Calibration c;
  read_calibration_sections(root, c);
  root.finish();
  return c;
}

std::string calibration_yaml(const Calibration& c) {
  std::ostringstream out;
  out << std::setprecision(17);
  out << "# Sensor mounts and local frame (docs/formats.md).\n"
      << "mru:\n  yaw_offset_deg: " << c.mru.yaw_offset_deg
      << "\n  deviation_cos_deg: " << c.mru.deviation_cos_deg
      << "\n  deviation_sin_deg: " << c.mru.deviation_sin_deg << "\n"
      << "dvl:\n  yaw_deg: " << c.dvl.yaw_deg << "\n  x_m: " << c.dvl.x_m
      << "\n  y_m: " << c.dvl.y_m << "\n  scale_factor: " << c.dvl.scale_factor << "\n"
      << (c.dvl.y_to_starboard ? "  y_axis: starboard\n" : "") << "sonar:\n  x_m: " << c.sonar.x_m
      << "\n  y_m: " << c.sonar.y_m
      << "\n  bearing_offset_deg: " << c.sonar.bearing_offset_rad / kDegToRad
      << "\n  bearing_sign: " << c.sonar.bearing_sign << "\n  z_m: " << c.sonar.z_m
      << "\n  time_offset_s: " << c.sonar.time_offset_s
      << "\n  range_scale: " << c.sonar.range_scale << "\n"
      << "frame:\n  origin_latitude_deg: " << c.frame.origin_latitude_deg
      << "\n  origin_longitude_deg: " << c.frame.origin_longitude_deg << "\n";
  return out.str();
}
}  // namespace

Calibration read_calibration(const std::string& path) {
  return calibration_from_yaml(io::load_yaml_file(path), path);
}

void write_calibration(const std::string& path, const Calibration& calibration) {
  const std::string text = calibration_yaml(calibration);
  io::write_text_atomically(path, text);
}

Calibration calibration_as_stored(const Calibration& calibration) {
  return calibration_from_yaml(YAML::Load(calibration_yaml(calibration)), "calibration.yaml");
}

}  // namespace msislab::settings
