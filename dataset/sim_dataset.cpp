#include "dataset/sim_dataset.hpp"

#include <cctype>
#include <cmath>
#include <filesystem>
#include <fstream>

#include "io/atomic_file.hpp"
#include "io/detections.hpp"
#include "io/geodesy.hpp"
#include "io/input_error.hpp"
#include "io/stpere_logs.hpp"
#include "io/text_lines.hpp"
#include "io/tum.hpp"
#include "settings/config_yaml.hpp"
#include "sim/navigation_sensors.hpp"

namespace msislab::dataset {

namespace fs = std::filesystem;

namespace {

/// File-name prefix from the scenario name: letters, digits, '-' and '_' only.
std::string prefix_of(const std::string& name) {
  std::string out;
  for (const char c : name)
    out += std::isalnum(static_cast<unsigned char>(c)) || c == '-' ? c : '_';
  return out.empty() ? "sim" : out;
}

std::vector<io::DvlRecord> dvl_records(const std::vector<sim::DvlSample>& samples) {
  std::vector<io::DvlRecord> rows;
  for (const sim::DvlSample& s : samples) {
    io::DvlRecord r;  // columns the simulator does not model stay 0
    r.t_log_s = s.t_s;
    r.bottom_vel_cm_s = {s.v_dvl_mps.x() * 100.0, s.v_dvl_mps.y() * 100.0, 0.0};
    r.bottom_vel_status = s.bottom_lock ? 1.0 : 0.0;
    r.range_bottom_m = {s.altitude_m, s.altitude_m, s.altitude_m};
    r.percent_good_pings = s.bottom_lock ? 100.0 : 0.0;
    rows.push_back(r);
  }
  return rows;
}

std::vector<io::MtiRecord> mti_records(const std::vector<sim::MruSample>& samples) {
  std::vector<io::MtiRecord> rows;
  for (const sim::MruSample& s : samples) {
    io::MtiRecord r;
    r.t_log_s = s.t_s;
    r.yaw_deg = s.yaw_mru_deg;
    r.accel_m_s2 = {0.0, 0.0, -9.81};
    rows.push_back(r);
  }
  return rows;
}

std::vector<io::GpsRecord> gps_records(const std::vector<sim::GpsFix>& fixes,
                                       const LocalFrame& frame) {
  const io::LocalProjection projection(frame);
  std::vector<io::GpsRecord> rows;
  for (const sim::GpsFix& f : fixes) {
    const auto [latitude_deg, longitude_deg] = projection.to_geodetic(f.p_world_m);
    io::GpsRecord r;
    r.t_log_s = f.t_s;
    r.latitude_nmea = io::degrees_to_nmea(latitude_deg);
    r.longitude_nmea = io::degrees_to_nmea(longitude_deg);
    r.status = 1.0;
    rows.push_back(r);
  }
  return rows;
}

std::vector<io::SonarBeamRecord> beam_records(const std::vector<sim::RenderedBeam>& beams,
                                              const SonarMount& mount) {
  std::vector<io::SonarBeamRecord> rows;
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

std::vector<io::BeamTimeRecord> beam_time_records(const std::vector<io::SonarBeamRecord>& beams) {
  std::vector<io::BeamTimeRecord> rows;
  rows.reserve(beams.size());
  for (const io::SonarBeamRecord& b : beams) rows.push_back({b.t_log_s, b.sensor_time_ms});
  return rows;
}

/// The detector's window for each keyframe (index 1 .. keyframes): the scenario's, or with
/// smoothing_bins 0 MATLAB's default window of that keyframe's kept bins, as smoothdata chooses it.
std::vector<int> keyframe_windows(const std::vector<io::SonarBeamRecord>& beams,
                                  const std::vector<std::pair<std::size_t, std::int32_t>>& swept,
                                  std::int32_t keyframes, const sim::Scenario& scenario) {
  const sim::DetectionModelConfig& d = scenario.detections;
  std::vector<int> windows(static_cast<std::size_t>(keyframes) + 1, d.smoothing_bins);
  if (d.smoothing_bins > 0) return windows;
  std::vector<std::vector<double>> rows;
  for (std::size_t k = 0; k < swept.size(); ++k) {
    rows.push_back(
        sim::kept_bins(beams[swept[k].first].intensity, scenario.sonar.bin_m, d.min_range_m));
    if (k + 1 == swept.size() || swept[k + 1].second != swept[k].second) {
      windows[static_cast<std::size_t>(swept[k].second)] =
          sim::matlab_default_window(rows, d.smoothing_factor);
      rows.clear();
    }
  }
  return windows;
}

/// The detections file as the real one is laid out: the detector of the scenario run on every
/// profile; keyframe k (from 1) is the k-th complete revolution, a sweep of the transducer angle
/// index from steps - 1 down to 0; beam_row is the beam's row in *_IS_timestamps.log. Beams
/// outside a complete revolution have no rows, as in the real file.
std::vector<io::DetectionRecord> detection_records(const std::vector<io::SonarBeamRecord>& beams,
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
    sim::DetectionModelConfig config = scenario.detections;
    config.smoothing_bins = windows[static_cast<std::size_t>(swept[k].second)];
    detected[k] = sim::detect_bins(beams[swept[k].first].intensity, scenario.sonar.bin_m, config);
    total += detected[k].size();
  }
  std::vector<io::DetectionRecord> rows;
  rows.reserve(total);
  for (std::size_t k = 0; k < swept.size(); ++k) {
    const auto [i, frame] = swept[k];
    const io::SonarBeamRecord& b = beams[i];
    const int idx = angle_index(i);
    for (const int j : detected[k]) {
      rows.push_back({frame, static_cast<std::int64_t>(i), b.t_log_s,
                      static_cast<std::int64_t>(b.sensor_time_ms), idx, idx * step_rad,
                      (j + 1) * scenario.sonar.bin_m});
    }
  }
  return rows;
}

std::vector<io::TumPose> truth_poses(const sim::VehicleTrajectory& truth, double depth_m) {
  // 10 Hz: every sample whose time is a new tenth of a second from the start.
  std::vector<io::TumPose> poses;
  double next_s = truth.start_s();
  for (const sim::VehicleState& s : truth.samples()) {
    if (s.t_s + 1e-9 < next_s) continue;
    poses.push_back({s.t_s, s.pose.x(), s.pose.y(), -depth_m, s.pose.yaw()});
    next_s += 0.1;
  }
  return poses;
}

/// The scenario's named time windows (truth/segments.csv), so `msislab run` scores them.
void write_segments(const std::string& path, const std::vector<TimeSegment>& segments) {
  io::write_file_atomically(path, [&](std::ostream& out) {
    std::string text = "name,begin_s,end_s\n";
    for (const TimeSegment& s : segments) {
      text += s.name + ",";
      io::append_number(text, s.begin_s);
      text += ",";
      io::append_number(text, s.end_s);
      text += "\n";
    }
    out << text;
  });
}

void write_files(const fs::path& dir, const sim::Scenario& scenario,
                 const sim::SimulationResult& result, const std::string& scenario_text) {
  const std::string base = (dir / prefix_of(scenario.name)).string();
  const DatasetRecords records = simulated_records(scenario, result, /*as_stored=*/false);
  io::write_is_log(base + "_IS.log", records.is_log);
  io::write_beam_times_log(base + "_IS_timestamps.log", records.beam_times);
  io::write_detections(base + "_detections.csv.gz", records.detections);
  io::write_setup_log(base + "_SETUP.log", records.setup);
  io::write_dvl_log(base + "_DVL.log", records.dvl);
  io::write_mti_log(base + "_MTi.log", records.mti);
  if (scenario.gps.enabled) io::write_gps_log(base + "_DGPS.log", records.gps);
  settings::write_calibration((dir / "calibration.yaml").string(), records.calibration);
  settings::write_navigation_noise((dir / "navigation_noise.yaml").string(),
                                   *records.navigation_noise);
  io::write_text_atomically((dir / "scenario.yaml").string(), scenario_text);
  fs::create_directories(dir / "truth");
  io::write_tum((dir / "truth" / "trajectory.tum").string(), records.truth_trajectory);
  io::write_beam_truth((dir / "truth" / "beams.csv").string(), beam_truth_rows(result.beams));
  write_segments((dir / "truth" / "segments.csv").string(), records.truth_segments);
}

}  // namespace

std::vector<io::BeamTruthRow> beam_truth_rows(const std::vector<sim::RenderedBeam>& beams) {
  std::vector<io::BeamTruthRow> rows;
  rows.reserve(beams.size());
  for (const sim::RenderedBeam& b : beams) {
    const sim::BeamTruth& t = b.truth;
    rows.push_back({b.slot.t_s, t.vehicle.x(), t.vehicle.y(), t.vehicle.yaw(),
                    t.bearing_vehicle_rad, t.first_hit_range_m, t.strongest_range_m,
                    t.strongest_is_multipath, t.strongest_surface, t.strongest_bearing_offset_rad});
  }
  return rows;
}

DatasetRecords simulated_records(const sim::Scenario& scenario, const sim::SimulationResult& result,
                                 bool as_stored) {
  DatasetRecords records;
  records.name = "simulated " + prefix_of(scenario.name) + " (seed " +
                 std::to_string(scenario.seed) + ", in memory)";
  const Calibration calibration = sim::calibration_of(scenario);
  records.calibration = as_stored ? settings::calibration_as_stored(calibration) : calibration;
  const NavigationNoise noise = sim::navigation_noise_of(scenario);
  records.navigation_noise = as_stored ? settings::navigation_noise_as_stored(noise) : noise;
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
    for (io::TumPose& pose : records.truth_trajectory)
      pose.yaw_rad = io::yaw_as_stored(pose.yaw_rad);
  }
  records.truth_segments = scenario.segments;
  return records;
}

void write_simulated_dataset(const io::OutputRequest& out, const sim::Scenario& scenario,
                             const sim::SimulationResult& result,
                             const std::string& scenario_text) {
  io::StagedFolder staged(out);
  write_files(staged.path(), scenario, result, scenario_text);
  staged.commit();
}

}  // namespace msislab::dataset
