#include "io/tum.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <optional>
#include <ostream>

#include "io/atomic_file.hpp"
#include "io/input_error.hpp"
#include "io/text_lines.hpp"

namespace msislab::io {
namespace {

constexpr std::array<std::string_view, 8> kNames = {"t", "x", "y", "z", "qx", "qy", "qz", "qw"};

// Yaw of the normalised quaternion: atan2(2 (qw qz + qx qy), 1 - 2 (qy^2 + qz^2)). Scaling by the
// largest component first keeps the norm from overflowing or underflowing.
/// nullopt for the zero quaternion.
std::optional<double> yaw_from_quaternion(std::array<double, 4> q) {
  double largest = 0.0;
  for (const double c : q) largest = std::max(largest, std::abs(c));
  if (largest == 0.0) return std::nullopt;
  for (double& c : q) c /= largest;
  const double norm = std::sqrt(q[0] * q[0] + q[1] * q[1] + q[2] * q[2] + q[3] * q[3]);
  const double qx = q[0] / norm;
  const double qy = q[1] / norm;
  const double qz = q[2] / norm;
  const double qw = q[3] / norm;
  return std::atan2(2.0 * (qw * qz + qx * qy), 1.0 - 2.0 * (qy * qy + qz * qz));
}

TumPose read_pose(const DataLines& lines) {
  lines.expect_columns(kNames.size());
  std::array<double, 8> v{};
  for (std::size_t i = 0; i < v.size(); ++i) v[i] = lines.number(i, kNames[i]);
  TumPose pose;
  pose.t_s = v[0];
  pose.x_m = v[1];
  pose.y_m = v[2];
  pose.z_m = v[3];
  const std::optional<double> yaw = yaw_from_quaternion({v[4], v[5], v[6], v[7]});
  if (!yaw) lines.fail("zero quaternion (qx = qy = qz = qw = 0) has no rotation");
  pose.yaw_rad = *yaw;
  return pose;
}

void append_pose(std::string& line, const TumPose& pose, const std::string& path, std::size_t row) {
  const std::array<double, 4> position = {pose.t_s, pose.x_m, pose.y_m, pose.z_m};
  for (std::size_t i = 0; i < position.size(); ++i) {
    append_finite(line, position[i], path, row, kNames[i]);
    line += ' ';
  }
  check_finite(pose.yaw_rad, path, row, "yaw");
  // A planar pose rotates about z only: q = (0, 0, sin(yaw/2), cos(yaw/2)).
  line += "0 0 ";
  append_number(line, std::sin(0.5 * pose.yaw_rad));
  line += ' ';
  append_number(line, std::cos(0.5 * pose.yaw_rad));
  line += '\n';
}

}  // namespace

std::vector<TumPose> read_tum(const std::string& path) {
  DataLines lines(path, '#');
  std::vector<TumPose> poses;
  while (lines.next()) {
    const TumPose pose = read_pose(lines);
    if (!poses.empty() && !(pose.t_s > poses.back().t_s))
      lines.fail("time does not increase (" + format_number(pose.t_s) + " after " +
                 format_number(poses.back().t_s) + ")");
    poses.push_back(pose);
  }
  require_data_rows(path, poses.size());
  return poses;
}

void write_tum(const std::string& path, const std::vector<TumPose>& poses) {
  write_file_atomically(path, [&](std::ostream& out) {
    out << "# t x y z qx qy qz qw\n";
    std::string line;
    for (std::size_t row = 0; row < poses.size(); ++row) {
      line.clear();
      append_pose(line, poses[row], path, row + 1);
      out.write(line.data(), static_cast<std::streamsize>(line.size()));
    }
  });
}

double yaw_as_stored(double yaw_rad) {
  return *yaw_from_quaternion({0.0, 0.0, std::sin(0.5 * yaw_rad), std::cos(0.5 * yaw_rad)});
}

}  // namespace msislab::io
