// A heading history for a scenario's vehicle (`vehicle.heading_csv`, docs/simulator.md): a CSV of
// `t_s,yaw_deg` rows, t_s from the run's start, yaw in the scene frame (x East, y North,
// counter-clockwise from x), time strictly increasing, at least two rows.
#pragma once

#include <Eigen/Core>
#include <string>
#include <vector>

namespace msislab::io {

inline constexpr const char* kHeadingCsvHeader = "t_s,yaw_deg";

/// Rows as (t_s, yaw_deg); InputError naming the file and line for a wrong header, a short row, a
/// value that is not a finite number, time that does not increase, or fewer than two rows.
std::vector<Eigen::Vector2d> read_heading_csv(const std::string& path);

/// Writes the rows atomically (the inverse of read_heading_csv).
void write_heading_csv(const std::string& path, const std::vector<Eigen::Vector2d>& rows);

}  // namespace msislab::io
