#include "io/sim_dataset.hpp"

#include <cctype>
#include <cmath>
#include <filesystem>
#include <fstream>

#include "io/atomic_file.hpp"
#include "io/config_yaml.hpp"
#include "io/detections.hpp"
#include "io/geodesy.hpp"
#include "io/input_error.hpp"
#include "io/stpere_logs.hpp"
#include "io/text_lines.hpp"
#include "io/tum.hpp"
#include "sim/navigation_sensors.hpp"

namespace msislab::io {

namespace fs = std::filesystem;

namespace {

/// File-name prefix from the scenario name: letters, digits, '-' and '_' only.
std::string prefix_of(const std::string& name) {
  std::string out;
  for (const char c : name)
    out += std::isalnum(static_cast<unsigned char>(c)) || c == '-' ? c : '_';
  return out.empty() ? "sim" : out;
}

std::vector<DvlRecord> dvl_records(const std::vector<sim::DvlSample>& samples) {
  std::vector<DvlRecord> rows;
  for (const sim::DvlSample& s : samples) {
    DvlRecord r;  // columns the simulator does not model stay 0
    r.t_log_s = s.t_s;
    r.bottom_vel_cm_s = {s.v_dvl_mps.x() * 100.0, s.v_dvl_mps.y() * 100.0, 0.0};
    r.bottom_vel_status = s.bottom_lock ? 1.0 : 0.0;
    r.range_bottom_m = {s.altitude_m, s.altitude_m, s.altitude_m};
    r.percent_good_pings = s.bottom_lock ? 100.0 : 0.0;
    rows.push_back(r);
  }
  return rows;
}

std::vector<MtiRecord> mti_records(const std::vector<sim::MruSample>& samples) {
  std::vector<MtiRecord> rows;
  for (const sim::MruSample& s : samples) {
    MtiRecord r;
    r.t_log_s = s.t_s;
    r.yaw_deg = s.yaw_mru_deg;
    r.accel_m_s2 = {0.0, 0.0, -9.81};
    rows.push_back(r);
  }
  return rows;
}

std::vector<GpsRecord> gps_records(const std::vector<sim::GpsFix>& fixes, const LocalFrame& frame) {
  const LocalProjection projection(frame);
  std::vector<GpsRecord> rows;
  for (const sim::GpsFix& f : fixes) {
    const auto [latitude_deg, longitude_deg] = projection.to_geodetic(f.p_world_m);
    GpsRecord r;
    r.t_log_s = f.t_s;
    r.latitude_nmea = degrees_to_nmea(latitude_deg);
    r.longitude_nmea = degrees_to_nmea(longitude_deg);
    r.status = 1.0;
    rows.push_back(r);
  }
  return rows;
}

std::vector<SonarBeamRecord> beam_records(const std::vector<sim::RenderedBeam>& beams,
                                          const SonarMount& mount) {
  std::vector<SonarBeamRecord> rows;
  rows.reserve(beams.size());
  for (const sim::RenderedBeam& b : beams) {
    // The head's own millisecond clock, counted from the first beam; the log time runs
    // time_offset_s behind the navigation clock, as the St. Pere sonar's does.
    const double sensor_ms = std::round((b.slot.t_s - beams.front().slot.t_s) * 1000.0);
    rows.push_back(
        {b.slot.t_s - mount.time_offset_s, sensor_ms, b.slot.transducer_angle_rad, b.intensity});
  }
  return rows;
}

std::vector<BeamTimeRecord> beam_time_records(const std::vector<SonarBeamRecord>& beams) {
  std::vector<BeamTimeRecord> rows;
  rows.reserve(beams.size());
  for (const SonarBeamRecord& b : beams) rows.push_back({b.t_log_s, b.sensor_time_ms});
  return rows;
}

/// The detector's window for each keyframe (index 1 .. keyframes): the scenario's, or with
/// smoothing_bins 0 MATLAB's default window of that keyframe's kept bins, as smoothdata chooses it.
std::vector<int> keyframe_windows(const std::vector<SonarBeamRecord>& beams,
                                  const std::vector<std::pair<std::size_t, std::int32_t>>& swept,
                                  std::int32_t keyframes, const sim::Scenario& scenario) {
  const DetectionModelConfig& d = scenario.detections;
  std::vector<int> windows(static_cast<std::size_t>(keyframes) + 1, d.smoothing_bins);
  if (d.smoothing_bins > 0) return windows;
  std::vector<std::vector<double>> rows;
  for (std::size_t k = 0; k < swept.size(); ++k) {
    rows.push_back(kept_bins(beams[swept[k].first].intensity, scenario.sonar.bin_m, d.min_range_m));
    if (k + 1 == swept.size() || swept[k + 1].second != swept[k].second) {
      windows[static_cast<std::size_t>(swept[k].second)] =
          matlab_default_window(rows, d.smoothing_factor);
      rows.clear();
    }
  }
  return windows;
}

/// The detections file as the real one is laid out: the detector of the scenario run on every
/// profile; keyframe k (from 1) is the k-th complete revolution, a sweep of the transducer angle
/// index from steps - 1 down to 0; beam_row is the beam's row in *_IS_timestamps.log. Beams
/// outside a complete revolution have no rows, as in the real file.
std::vector<DetectionRecord> detection_records(const std::vector<SonarBeamRecord>& beams,
                                               const sim::Scenario& scenario) {
  const int steps = scenario.sonar.steps_per_revolution;
  const double step_rad = 2.0 * M_PI / steps;
  const auto angle_index = [&](std::size_t i) {
    const long k = std::lround(beams[i].transducer_angle_rad / step_rad);
    return static_cast<int>(((k % steps) + steps) % steps);
  };
  // The detected bins of every beam of a complete revolution first, so the rows (a million on
  // the St. Pere replica) are laid out once.
  std::vector<std::pair<std::size_t, std::int32_t>> swept;  // beam, keyframe
  std::int32_t keyframe = 0;
  for (std::size_t start = 0; start + static_cast<std::size_t>(steps) <= beams.size(); ++start) {
    if (angle_index(start) != steps - 1) continue;
    ++keyframe;
    for (std::size_t i = start; i < start + static_cast<std::size_t>(steps); ++i) {
      swept.emplace_back(i, keyframe);
    }
    start += static_cast<std::size_t>(steps) - 1;
  }
  const std::vector<int> windows = keyframe_windows(beams, swept, keyframe, scenario);
  std::vector<std::vector<int>> detected(swept.size());
  std::size_t total = 0;
  for (std::size_t k = 0; k < swept.size(); ++k) {
    DetectionModelConfig config = scenario.detections;
    config.smoothing_bins = windows[static_cast<std::size_t>(swept[k].second)];
    detected[k] = detect_bins(beams[swept[k].first].intensity, scenario.sonar.bin_m, config);
    total += detected[k].size();
  }
  std::vector<DetectionRecord> rows;
  rows.reserve(total);
  for (std::size_t k = 0; k < swept.size(); ++k) {
    const auto [i, frame] = swept[k];
    const SonarBeamRecord& b = beams[i];
    const int idx = angle_index(i);
    for (const int j : detected[k]) {
      rows.push_back({frame, static_cast<std::int64_t>(i), b.t_log_s,
                      static_cast<std::int64_t>(b.sensor_time_ms), idx, idx * step_rad,
                      (j + 1) * scenario.sonar.bin_m});
    }
  }
  return rows;
}

std::vector<TumPose> truth_poses(const sim::VehicleTrajectory& truth, double depth_m) {
  // 10 Hz: every sample whose time is a new tenth of a second from the start.
  std::vector<TumPose> poses;
  double next_s = truth.start_s();
  for (const sim::VehicleState& s : truth.samples()) {
    if (s.t_s + 1e-9 < next_s) continue;
    poses.push_back({s.t_s, s.pose.x(), s.pose.y(), -depth_m, s.pose.yaw()});
    next_s += 0.1;
  }
  return poses;
}

std::string optional_number(const std::optional<double>& value) {
  return value ? format_number(*value) : std::string();
}

/// The scenario's named time windows (truth/segments.csv), so `msislab run` scores them.
void write_segments(const std::string& path, const std::vector<TimeSegment>& segments) {
  write_file_atomically(path, [&](std::ostream& out) {
    std::string text = "name,begin_s,end_s\n";
    for (const TimeSegment& s : segments) {
      text += s.name + ",";
      append_number(text, s.begin_s);
      text += ",";
      append_number(text, s.end_s);
      text += "\n";
    }
    out << text;
  });
}

void write_files(const fs::path& dir, const sim::Scenario& scenario,
                 const sim::SimulationResult& result, const std::string& scenario_text) {
  const std::string base = (dir / prefix_of(scenario.name)).string();
  const DatasetRecords records = simulated_records(scenario, result, /*as_stored=*/false);
  write_is_log(base + "_IS.log", records.is_log);
  write_beam_times_log(base + "_IS_timestamps.log", records.beam_times);
  write_detections(base + "_detections.csv.gz", records.detections);
  write_setup_log(base + "_SETUP.log", records.setup);
  write_dvl_log(base + "_DVL.log", records.dvl);
  write_mti_log(base + "_MTi.log", records.mti);
  if (scenario.gps.enabled) write_gps_log(base + "_DGPS.log", records.gps);
  write_calibration((dir / "calibration.yaml").string(), records.calibration);
  write_navigation_noise((dir / "navigation_noise.yaml").string(), *records.navigation_noise);
  write_text_atomically((dir / "scenario.yaml").string(), scenario_text);
  fs::create_directories(dir / "truth");
  write_tum((dir / "truth" / "trajectory.tum").string(), records.truth_trajectory);
  write_beam_truth((dir / "truth" / "beams.csv").string(), result.beams);
  write_segments((dir / "truth" / "segments.csv").string(), records.truth_segments);
}

}  // namespace

void write_beam_truth(const std::string& path, const std::vector<sim::RenderedBeam>& beams) {
  write_file_atomically(path, [&](std::ostream& out) {
    std::string text =
        "t_s,x_m,y_m,yaw_rad,bearing_rad,first_hit_range_m,strongest_range_m,"
        "strongest_multipath,strongest_surface\n";
    for (const sim::RenderedBeam& b : beams) {
      const sim::BeamTruth& t = b.truth;
      for (const double v :
           {b.slot.t_s, t.vehicle.x(), t.vehicle.y(), t.vehicle.yaw(), t.bearing_vehicle_rad}) {
        append_number(text, v);
        text += ',';
      }
      text += optional_number(t.first_hit_range_m) + "," + optional_number(t.strongest_range_m) +
              "," + (t.strongest_is_multipath ? "1" : "0") + "," + t.strongest_surface + "\n";
    }
    out << text;
  });
}

DatasetRecords simulated_records(const sim::Scenario& scenario, const sim::SimulationResult& result,
                                 bool as_stored) {
  DatasetRecords records;
  records.name = "simulated " + prefix_of(scenario.name) + " (seed " +
                 std::to_string(scenario.seed) + ", in memory)";
  const Calibration calibration = sim::calibration_of(scenario);
  records.calibration = as_stored ? calibration_as_stored(calibration) : calibration;
  const NavigationNoise noise = sim::navigation_noise_of(scenario);
  records.navigation_noise = as_stored ? navigation_noise_as_stored(noise) : noise;
  records.is_log = beam_records(result.beams, scenario.sonar.mount);
  records.beam_times = beam_time_records(records.is_log);
  records.detections = detection_records(records.is_log, scenario);
  records.has_detections = true;
  records.setup = {scenario.sonar.bins * scenario.sonar.bin_m, scenario.sonar.bin_m,
                   2.0 * M_PI / scenario.sonar.steps_per_revolution};
  records.dvl = dvl_records(result.dvl);
  records.mti = mti_records(result.mru);
  if (scenario.gps.enabled) records.gps = gps_records(result.gps, scenario.gps.frame);
  records.truth_trajectory = truth_poses(result.truth, scenario.vehicle.depth_m);
  if (as_stored) {
    for (TumPose& pose : records.truth_trajectory) pose.yaw_rad = yaw_as_stored(pose.yaw_rad);
  }
  records.truth_segments = scenario.segments;
  return records;
}

void write_simulated_dataset(const OutputRequest& out, const sim::Scenario& scenario,
                             const sim::SimulationResult& result,
                             const std::string& scenario_text) {
  StagedFolder staged(out);
  write_files(staged.path(), scenario, result, scenario_text);
  staged.commit();
}

}  // namespace msislab::io
