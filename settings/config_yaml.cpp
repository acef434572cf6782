#include "settings/config_yaml.hpp"

#include <algorithm>
#include <cctype>
#include <cmath>

#include "geometry/angles.hpp"
#include "io/input_error.hpp"
#include "io/text_lines.hpp"
#include "settings/config_fields.hpp"
#include "settings/footprint_yaml.hpp"

namespace msislab::settings {

void require_positive(io::YamlMap& map, const std::string& key, double value) {
  if (!(value > 0.0)) map.fail(key, "must be > 0, got " + std::to_string(value));
}

void read_count(io::YamlMap& map, const std::string& key, int& value, int min, int max) {
  long long v = value;
  if (map.integer(key, v) && (v < min || v > max)) {
    map.fail(key, "must be in [" + std::to_string(min) + ", " + std::to_string(max) + "]");
  }
  value = static_cast<int>(v);
}

void read_line_normals(io::YamlMap& map, LineNormalConfig& line) {
  map.number("line_radius_m", line.radius_m);
  require_positive(map, "line_radius_m", line.radius_m);
  read_count(map, "line_min_points", line.min_points, 3, 100000);
  map.number("line_max_eigen_ratio", line.max_eigen_ratio);
  require_positive(map, "line_max_eigen_ratio", line.max_eigen_ratio);
}

void read_mru_mount(io::YamlMap& map, MruMount& mount) {
  map.number("yaw_offset_deg", mount.yaw_offset_deg);
}

void read_dvl_mount(io::YamlMap& map, DvlMount& mount) {
  map.number("yaw_deg", mount.yaw_deg);
  map.number("x_m", mount.x_m);
  map.number("y_m", mount.y_m);
  if (std::string y_axis; map.text("y_axis", y_axis)) {
    if (y_axis != "port" && y_axis != "starboard") {
      map.fail("y_axis", "must be 'port' or 'starboard', got '" + y_axis + "'");
    }
    mount.y_to_starboard = y_axis == "starboard";
  }
}

void read_sonar_mount(io::YamlMap& map, SonarMount& mount) {
  map.number("x_m", mount.x_m);
  map.number("y_m", mount.y_m);
  map.number("z_m", mount.z_m);
  double bearing_offset_deg = mount.bearing_offset_rad / kDegToRad;
  if (map.number("bearing_offset_deg", bearing_offset_deg)) {
    mount.bearing_offset_rad = bearing_offset_deg * kDegToRad;
  }
  if (map.number("bearing_sign", mount.bearing_sign) && std::abs(mount.bearing_sign) != 1.0) {
    map.fail("bearing_sign", "must be 1 or -1");
  }
  if (map.number("time_offset_s", mount.time_offset_s) && std::abs(mount.time_offset_s) > 60.0) {
    map.fail("time_offset_s", "must be within [-60, 60] s");
  }
}

void read_local_frame(io::YamlMap& map, LocalFrame& frame) {
  map.number("origin_latitude_deg", frame.origin_latitude_deg);
  map.number("origin_longitude_deg", frame.origin_longitude_deg);
  if (std::abs(frame.origin_latitude_deg) > 84.0) {
    map.fail("origin_latitude_deg", "outside the UTM range [-84, 84]");
  }
  if (std::abs(frame.origin_longitude_deg) > 180.0) {
    map.fail("origin_longitude_deg", "outside [-180, 180]");
  }
}

namespace {

void read_dead_reckoning(io::YamlMap map, DeadReckoningConfig& c) {
  map.number("dvl_sigma_mps", c.dvl_sigma_mps);
  double heading_sigma_deg = c.heading_sigma_rad / kDegToRad;
  if (map.number("heading_sigma_deg", heading_sigma_deg)) {
    c.heading_sigma_rad = heading_sigma_deg * kDegToRad;
  }
  map.number("accel_sigma_mps2", c.accel_sigma_mps2);
  map.number("yaw_accel_sigma_radps2", c.yaw_accel_sigma_radps2);
  map.number("initial_velocity_sigma_mps", c.initial_velocity_sigma_mps);
  map.number("initial_yaw_rate_sigma_radps", c.initial_yaw_rate_sigma_radps);
  map.number("dvl_gate_chi2", c.dvl_gate_chi2);
  map.number("heading_bias_walk_deg_per_sqrt_s", c.heading_bias_walk_deg_per_sqrt_s);
  if (c.heading_bias_walk_deg_per_sqrt_s < 0.0) {
    map.fail("heading_bias_walk_deg_per_sqrt_s", "must be >= 0 (0: no bias walk)");
  }
  map.number("heading_bias_sigma_deg", c.heading_bias_sigma_deg);
  if (c.heading_bias_sigma_deg < 0.0) map.fail("heading_bias_sigma_deg", "must be >= 0");
  map.number("dvl_scale_sigma", c.dvl_scale_sigma);
  if (!(c.dvl_scale_sigma >= 0.0 && c.dvl_scale_sigma < 0.5)) {
    map.fail("dvl_scale_sigma", "must be in [0, 0.5)");
  }
  require_positive(map, "dvl_sigma_mps", c.dvl_sigma_mps);
  require_positive(map, "heading_sigma_deg", c.heading_sigma_rad);
  require_positive(map, "accel_sigma_mps2", c.accel_sigma_mps2);
  require_positive(map, "yaw_accel_sigma_radps2", c.yaw_accel_sigma_radps2);
  require_positive(map, "initial_velocity_sigma_mps", c.initial_velocity_sigma_mps);
  require_positive(map, "initial_yaw_rate_sigma_radps", c.initial_yaw_rate_sigma_radps);
  map.finish();
}

void read_segmentation(io::YamlMap map, SegmentationConfig& c) {
  std::string source;
  if (map.text("source", source)) {
    if (source == "auto") {
      c.source = SonarSource::kAuto;
    } else if (source == "raw") {
      c.source = SonarSource::kRaw;
    } else if (source == "detections") {
      c.source = SonarSource::kDetections;
    } else {
      map.fail("source", "unknown source '" + source + "' (auto, raw, detections)");
    }
  }
  std::string method;
  if (map.text("method", method) && !parse_segmentation_method(method, c.method)) {
    map.fail("method",
             "unknown method '" + method + "' (max_intensity, threshold_groups, smoothed_first)");
  }
  map.number("min_range_m", c.min_range_m);
  map.number("threshold", c.threshold);
  long long count = c.max_ranges_per_beam;
  if (map.integer("max_ranges_per_beam", count) && (count < 1 || count > 100)) {
    map.fail("max_ranges_per_beam", "must be in [1, 100]");
  }
  c.max_ranges_per_beam = static_cast<int>(count);
  count = c.min_run_bins;
  if (map.integer("min_run_bins", count) && (count < 1 || count > 1000)) {
    map.fail("min_run_bins", "must be in [1, 1000]");
  }
  c.min_run_bins = static_cast<int>(count);
  count = c.smoothing_bins;
  if (map.integer("smoothing_bins", count) && (count < 1 || count % 2 == 0 || count > 101)) {
    map.fail("smoothing_bins", "must be odd, in [1, 101]");
  }
  c.smoothing_bins = static_cast<int>(count);
  map.number("sigma_range_m", c.sigma_range_m);
  require_positive(map, "sigma_range_m", c.sigma_range_m);
  double sigma_bearing_deg = c.sigma_bearing_rad / kDegToRad;
  if (map.number("sigma_bearing_deg", sigma_bearing_deg)) {
    c.sigma_bearing_rad = sigma_bearing_deg * kDegToRad;
  }
  require_positive(map, "sigma_bearing_deg", c.sigma_bearing_rad);
  if (c.min_range_m < 0.0) map.fail("min_range_m", "must be >= 0");
  map.finish();
}

void read_matching(io::YamlMap map, ScanMatchConfig& c) {
  map.number("association_gate_chi2", c.association_gate_chi2);
  require_positive(map, "association_gate_chi2", c.association_gate_chi2);
  read_count(map, "max_iterations", c.max_iterations, 1, 1000);
  read_count(map, "min_inliers", c.min_inliers, 3, 100000);
  map.boolean("scale_covariance_by_residual", c.scale_covariance_by_residual);
  map.boolean("shared_point_errors", c.shared_point_errors);
  map.boolean("point_to_line_covariance", c.point_to_line_covariance);
  map.boolean("point_to_line_estimate", c.point_to_line_estimate);
  map.boolean("reciprocal_association", c.reciprocal_association);
  read_line_normals(map, c.line);
  map.finish();
}

void read_validation(io::YamlMap map, MatchValidationConfig& c) {
  map.number("restart_offset_m", c.restart_offset_m);
  if (c.restart_offset_m < 0.0) map.fail("restart_offset_m", "must be >= 0 (0: no restarts)");
  map.number("max_kept_fraction", c.max_kept_fraction);
  if (!(c.max_kept_fraction > 0.0 && c.max_kept_fraction < 1.0)) {
    map.fail("max_kept_fraction", "must be in (0, 1)");
  }
  map.number("ambiguity_probability", c.ambiguity_probability);
  if (!(c.ambiguity_probability > 0.0 && c.ambiguity_probability < 1.0)) {
    map.fail("ambiguity_probability", "must be in (0, 1)");
  }
  map.number("ambiguity_min_fraction", c.ambiguity_min_fraction);
  if (!(c.ambiguity_min_fraction >= 0.0 && c.ambiguity_min_fraction < 1.0)) {
    map.fail("ambiguity_min_fraction", "must be in [0, 1)");
  }
  map.number("min_overlap", c.min_overlap);
  if (!(c.min_overlap >= 0.0 && c.min_overlap <= 1.0)) map.fail("min_overlap", "must be in [0, 1]");
  map.boolean("initial_guess_term", c.initial_guess_term);
  map.finish();
}

void read_calibration_states(io::YamlMap map, CalibrationStatesConfig& c,
                             const DeadReckoningConfig& compass) {
  map.boolean("range_scale", c.range_scale);
  map.number("range_scale_prior", c.range_scale_prior);
  require_positive(map, "range_scale_prior", c.range_scale_prior);
  map.number("range_scale_sigma", c.range_scale_sigma);
  require_positive(map, "range_scale_sigma", c.range_scale_sigma);
  map.boolean("dvl_scale", c.dvl_scale);
  map.number("dvl_scale_prior", c.dvl_scale_prior);
  require_positive(map, "dvl_scale_prior", c.dvl_scale_prior);
  map.number("dvl_scale_sigma", c.dvl_scale_sigma);
  require_positive(map, "dvl_scale_sigma", c.dvl_scale_sigma);
  map.boolean("clock_offset", c.clock_offset);
  map.number("clock_offset_prior_s", c.clock_offset_prior_s);
  if (std::abs(c.clock_offset_prior_s) > 60.0) {
    map.fail("clock_offset_prior_s", "must be within [-60, 60] s");
  }
  map.number("clock_offset_sigma_s", c.clock_offset_sigma_s);
  require_positive(map, "clock_offset_sigma_s", c.clock_offset_sigma_s);
  map.boolean("compass_deviation", c.compass_deviation);
  for (auto [key, value] :
       {std::pair<const char*, double*>{"compass_deviation_cos_prior_deg",
                                        &c.compass_deviation_cos_prior_deg},
        {"compass_deviation_sin_prior_deg", &c.compass_deviation_sin_prior_deg}}) {
    if (map.number(key, *value) && std::abs(*value) >= 45.0) map.fail(key, "must be under 45 deg");
  }
  map.number("compass_deviation_sigma_deg", c.compass_deviation_sigma_deg);
  require_positive(map, "compass_deviation_sigma_deg", c.compass_deviation_sigma_deg);
  // The compass's bias model is the dead reckoning's (the sensor's), in one place; the state is on
  // where the model has a bias unless the config says otherwise.
  c.heading_bias_walk_deg_per_sqrt_s = compass.heading_bias_walk_deg_per_sqrt_s;
  c.heading_bias_sigma_deg = compass.heading_bias_sigma_deg;
  if (!map.boolean("heading_bias", c.heading_bias)) {
    c.heading_bias = c.heading_bias_walk_deg_per_sqrt_s > 0.0 || c.heading_bias_sigma_deg > 0.0;
  }
  if (c.heading_bias &&
      !(c.heading_bias_walk_deg_per_sqrt_s > 0.0 || c.heading_bias_sigma_deg > 0.0)) {
    map.fail("heading_bias",
             "needs the compass's bias model: dead_reckoning.heading_bias_walk_deg_per_sqrt_s or "
             "heading_bias_sigma_deg above 0");
  }
  map.finish();
}

void read_trajectory_slam(io::YamlMap map, SlamConfig& config) {
  ScanFrontEndConfig& f = config.trajectory_slam.front_end;
  map.number("association_distance_m", f.association_distance_m);
  require_positive(map, "association_distance_m", f.association_distance_m);
  read_count(map, "max_matches_per_scan", f.max_matches_per_scan, 0, 1000);
  read_count(map, "min_scan_gap", f.min_scan_gap, 1, 1000000);
  read_count(map, "iekf_iterations", f.iekf_iterations, 1, 100);
  map.number("innovation_gate_chi2", f.innovation_gate_chi2);
  require_positive(map, "innovation_gate_chi2", f.innovation_gate_chi2);
  map.boolean("compass_updates", f.compass_updates);
  map.number("compass_gate_chi2", f.compass_gate_chi2);
  require_positive(map, "compass_gate_chi2", f.compass_gate_chi2);
  map.boolean("joint_update", f.joint_update);
  TrajectoryFilterConfig& filter = config.trajectory_slam.filter;
  map.boolean("match_cross_covariance", filter.match_cross_covariance);
  map.boolean("update_whole_state", filter.update_whole_state);
  if (std::string held; map.text("scan_shared_errors", held)) {
    if (held == "none") {
      filter.scan_shared_errors = ScanSharedErrors::kNone;
    } else if (held == "motion") {
      filter.scan_shared_errors = ScanSharedErrors::kMotion;
    } else if (held == "motion_and_points") {
      filter.scan_shared_errors = ScanSharedErrors::kMotionAndPoints;
    } else {
      map.fail("scan_shared_errors",
               "unknown value '" + held + "' (none, motion, motion_and_points)");
    }
  }
  read_count(map, "linearisation_samples", config.linearisation_samples, 0, 1000000);
  read_matching(map.map("matching"), f.matching);
  read_validation(map.map("validation"), f.validation);
  read_calibration_states(map.map("calibration"), config.trajectory_slam.calibration,
                          config.dead_reckoning);
  map.finish();
}

void read_pose_graph(io::YamlMap map, PoseGraphSlamConfig& c) {
  std::string loss;
  if (map.text("robust_loss", loss)) {
    if (loss == "dcs") {
      c.graph.robust_loss = RobustLoss::kDynamicCovarianceScaling;
    } else if (loss == "cauchy") {
      c.graph.robust_loss = RobustLoss::kCauchy;
    } else {
      map.fail("robust_loss", "unknown loss '" + loss + "' (dcs, cauchy)");
    }
  }
  map.number("robust_scale_chi2", c.graph.robust_scale_chi2);
  if (c.graph.robust_scale_chi2 < 0.0) map.fail("robust_scale_chi2", "must be >= 0 (0: no loss)");
  map.number("robust_start_factor", c.graph.robust_start_factor);
  if (c.graph.robust_start_factor < 1.0) map.fail("robust_start_factor", "must be >= 1");
  read_count(map, "max_iterations", c.graph.max_iterations, 1, 100000);
  read_count(map, "solve_every", c.solve_every, 1, 1000000);
  read_count(map, "online_window_scans", c.online_window_scans, 0, 1000000);
  read_count(map, "online_old_nodes", c.online_old_nodes, 0, 1000000);
  read_count(map, "online_old_chain_scans", c.online_old_chain_scans, 0, 1000000);
  map.finish();
}

}  // namespace

std::vector<TimeSegment> read_segments(io::YamlMap map) {
  std::vector<TimeSegment> segments;
  for (const std::string& name : map.keys()) {
    const bool plain = !name.empty() && std::all_of(name.begin(), name.end(), [](char c) {
      return std::isalnum(static_cast<unsigned char>(c)) || c == '_' || c == '-';
    });
    if (!plain) map.fail(name, "a segment name is letters, digits, '_' or '-'");
    std::vector<double> window;
    map.numbers(name, window);
    if (window.size() != 2 || !(window[0] < window[1])) {
      map.fail(name, "expected [begin_s, end_s] with begin_s < end_s");
    }
    segments.push_back({name, window[0], window[1]});
  }
  map.finish();
  return segments;
}

SlamConfig slam_config_of(const YAML::Node& node, const std::string& path, const SlamConfig& base) {
  io::YamlMap root(node, path, "");
  SlamConfig config = base;
  std::string noise;
  if (root.text("navigation_noise", noise)) {
    if (noise != "dataset" && noise != "config") {
      root.fail("navigation_noise", "must be 'dataset' or 'config', got '" + noise + "'");
    }
    config.navigation_noise_from_dataset = noise == "dataset";
  }
  read_dead_reckoning(root.map("dead_reckoning"), config.dead_reckoning);
  read_segmentation(root.map("segmentation"), config.segmentation);
  read_footprint_section(root.map("footprint"), config.footprint);
  read_trajectory_slam(root.map("trajectory_slam"), config);
  read_pose_graph(root.map("pose_graph"), config.pose_graph);
  config.segments = read_segments(root.map("segments"));
  root.finish();
  return config;
}

SlamConfig read_slam_config(const std::string& path) {
  return slam_config_of(io::load_yaml_file(path), path, SlamConfig{});
}

SlamConfig read_slam_config_text(const std::string& text, const std::string& name) {
  return slam_config_of(io::load_yaml_text(text, name), name, SlamConfig{});
}

}  // namespace msislab::settings
