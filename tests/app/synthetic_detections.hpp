// A small sonar dataset in the St. Pere detection formats, with statistics known by construction:
// PREFIX_IS_timestamps.log, PREFIX_SETUP.log and PREFIX_detections.csv.gz, the keyframes being
// consecutive revolutions of 200 beams (angle_idx 199 down to 0, like the real file) between a few
// beams before the first and after the last.
#pragma once

#include <cmath>
#include <filesystem>
#include <string>
#include <vector>

#include "io/detections.hpp"
#include "io/stpere_logs.hpp"

namespace msislab::testing {

struct DetectionPattern {
  std::string prefix = "synth";
  int keyframes = 3;
  int lead_beams = 5;  ///< beams before the first keyframe (not counted)
  int tail_beams = 3;  ///< beams after the last keyframe (not counted)
  /// Beam j of a keyframe (0-based) has detections when j % period < detected_per_period.
  int period = 2;
  int detected_per_period = 1;
  /// The d-th beam with detections of a keyframe (0-based) starts at first_m + (d % 10) m with a
  /// run of 5 bins; when d % 10 == 0 a second run of 3 bins follows 3 m further out.
  double first_m = 10.0;
  double beam_interval_s = 0.069;  ///< 200 beams in 13.8 s
};

inline constexpr int kSyntheticBeamsPerRevolution = 200;

/// Writes the three files into dir (created) and returns the detections file's path.
inline std::string write_detection_dataset(const std::filesystem::path& dir,
                                           const DetectionPattern& p = {}) {
  std::filesystem::create_directories(dir);
  constexpr int kSteps = kSyntheticBeamsPerRevolution;
  const int beams = p.lead_beams + p.keyframes * kSteps + p.tail_beams;
  std::vector<io::BeamTimeRecord> times;
  for (int i = 0; i < beams; ++i) {
    const double t_s = 1.0e9 + i * p.beam_interval_s;
    times.push_back({t_s, std::round(1000.0 * (t_s - 1.0e9))});
  }
  std::vector<io::DetectionRecord> rows;
  for (int k = 0; k < p.keyframes; ++k) {
    int d = 0;
    for (int j = 0; j < kSteps; ++j) {
      if (j % p.period >= p.detected_per_period) continue;
      const int row = p.lead_beams + k * kSteps + j;
      const int angle_idx = kSteps - 1 - j;
      const auto add = [&](double range_m) {
        rows.push_back({k + 1, row, times[row].t_log_s,
                        static_cast<std::int64_t>(times[row].sensor_time_ms), angle_idx,
                        angle_idx * 2.0 * M_PI / kSteps, range_m});
      };
      const double first_m = p.first_m + d % 10;
      for (int b = 0; b < 5; ++b) add(first_m + 0.1 * b);
      if (d % 10 == 0) {
        for (int b = 0; b < 3; ++b) add(first_m + 3.0 + 0.1 * b);
      }
      ++d;
    }
  }
  io::write_beam_times_log((dir / (p.prefix + "_IS_timestamps.log")).string(), times);
  io::write_setup_log((dir / (p.prefix + "_SETUP.log")).string(), io::SonarSetup{});
  const std::string detections = (dir / (p.prefix + "_detections.csv.gz")).string();
  io::write_detections(detections, rows);
  return detections;
}

}  // namespace msislab::testing
