// A small noise-free synthetic dataset for the app tests, written with the io writers: a vehicle
// driving a known smooth path (slow turns, a little sway) with DVL at 1.5 Hz, MTi at 10 Hz and the
// exact truth/trajectory.tum at 10 Hz, in the St. Pere formats and calibration.
#pragma once

#include <Eigen/Core>
#include <algorithm>
#include <cmath>
#include <cstddef>
#include <filesystem>
#include <string>
#include <vector>

#include "geometry/calibration.hpp"
#include "io/stpere_logs.hpp"
#include "io/tum.hpp"
#include "test_support.hpp"

namespace msislab::testing {

struct SyntheticOptions {
  double duration_s = 600.0;
  double speed_mps = 0.3;  ///< surge
  double depth_m = 1.5;
  bool write_truth = true;  ///< false: no truth/ folder (and no GPS), so the run has no metrics
  std::string prefix = "synth";
};

/// Log time of the first sample (Unix seconds, like the real logs).
constexpr double kSyntheticT0_s = 1.0e9;
constexpr double kSyntheticPi = 3.14159265358979323846;

/// Vehicle yaw (rad) t_s seconds after the start: a slow drift with a gentle weave.
inline double synthetic_yaw_rad(double t_s) {
  return 0.3 + 0.004 * t_s + 0.4 * std::sin(2.0 * kSyntheticPi * t_s / 150.0);
}

/// Vehicle-frame velocity (surge, sway) in m/s t_s seconds after the start.
inline Eigen::Vector2d synthetic_velocity_mps(double t_s, double speed_mps) {
  return {speed_mps, 0.03 * std::sin(2.0 * kSyntheticPi * t_s / 90.0)};
}

inline Eigen::Matrix2d rotation(double angle_rad) {
  Eigen::Matrix2d R;
  R << std::cos(angle_rad), -std::sin(angle_rad), std::sin(angle_rad), std::cos(angle_rad);
  return R;
}

/// Writes PREFIX_DVL.log, PREFIX_MTi.log and (optionally) truth/trajectory.tum into dir and returns
/// the truth poses (10 Hz, starting at kSyntheticT0_s at the world origin).
inline std::vector<io::TumPose> write_synthetic_dataset(const std::filesystem::path& dir,
                                                        const SyntheticOptions& options = {}) {
  std::filesystem::create_directories(dir);
  const Calibration calibration;  // the St. Pere mounts, as read when calibration.yaml is absent
  // Exact positions: midpoint integration over 10 ms steps (error far below a millimetre).
  constexpr int kStepsPerTruthSample = 10;
  constexpr double kStep_s = 0.01;
  const auto samples = static_cast<std::size_t>(std::lround(options.duration_s * 10.0)) + 1;
  std::vector<io::TumPose> truth;
  std::vector<io::MtiRecord> mti;
  Eigen::Vector2d p_world_m = Eigen::Vector2d::Zero();
  for (std::size_t k = 0; k < samples; ++k) {
    const double t_s = static_cast<double>(k) / 10.0;
    const double yaw_rad = synthetic_yaw_rad(t_s);
    truth.push_back(
        {kSyntheticT0_s + t_s, p_world_m.x(), p_world_m.y(), -options.depth_m, yaw_rad});
    io::MtiRecord row;
    row.t_log_s = kSyntheticT0_s + t_s;
    row.yaw_deg = mru_yaw_from_vehicle(yaw_rad, calibration.mru);
    mti.push_back(row);
    for (int j = 0; j < kStepsPerTruthSample; ++j) {
      const double t_mid_s = t_s + (j + 0.5) * kStep_s;
      p_world_m += rotation(synthetic_yaw_rad(t_mid_s)) *
                   synthetic_velocity_mps(t_mid_s, options.speed_mps) * kStep_s;
    }
  }
  // DVL bottom velocity in cm/s in the DVL frame: the inverse of the mount rotation.
  const Eigen::Matrix2d R_dvl_vehicle =
      rotation(calibration.dvl.yaw_deg * kSyntheticPi / 180.0).transpose();
  std::vector<io::DvlRecord> dvl;
  for (std::size_t k = 0; static_cast<double>(k) / 1.5 <= options.duration_s; ++k) {
    const double t_s = static_cast<double>(k) / 1.5;
    const Eigen::Vector2d v_dvl_cm_s =
        100.0 * R_dvl_vehicle * synthetic_velocity_mps(t_s, options.speed_mps);
    io::DvlRecord row;
    row.t_log_s = kSyntheticT0_s + t_s;
    row.bottom_vel_cm_s = {v_dvl_cm_s.x(), v_dvl_cm_s.y(), 0.0};
    row.bottom_vel_status = 1.0;
    row.range_bottom_m = {options.depth_m, options.depth_m, options.depth_m};
    dvl.push_back(row);
  }
  io::write_dvl_log((dir / (options.prefix + "_DVL.log")).string(), dvl);
  io::write_mti_log((dir / (options.prefix + "_MTi.log")).string(), mti);
  if (options.write_truth) {
    std::filesystem::create_directories(dir / "truth");
    io::write_tum((dir / "truth" / "trajectory.tum").string(), truth);
  }
  return truth;
}

/// Cuts the last data line of a text file in half (a truncated log) and returns its 1-based line
/// number.
inline std::size_t truncate_last_line(const std::string& path) {
  std::string text = read_text(path);
  while (!text.empty() && text.back() == '\n') text.pop_back();
  const std::size_t start = text.rfind('\n') + 1;
  const std::size_t line = static_cast<std::size_t>(std::count(text.begin(), text.end(), '\n')) + 1;
  text.resize(start + (text.size() - start) / 2);
  write_text(path, text + "\n");
  return line;
}

}  // namespace msislab::testing
