// The simulator's per-beam truth, truth/beams.csv (docs/formats.md): its rows, reader and writer
// (dataset/sim_dataset writes a simulation's beams through it). The reader is strict: the exact
// header, 10 comma-separated fields (9 in a dataset simulated before the strongest echo's bearing
// was written), finite numbers, an empty field only for the optional ranges, multipath 0 or 1, time
// never going backwards; any other line is an InputError "file:line: what".
#pragma once

#include <optional>
#include <string>
#include <vector>

namespace msislab::io {

/// One row of truth/beams.csv: one sonar beam.
struct BeamTruthRow {
  double t_s = 0.0;  ///< transmit time (log clock)
  double x_m = 0.0;  ///< true vehicle pose at transmit, world frame
  double y_m = 0.0;
  double yaw_rad = 0.0;
  double bearing_rad = 0.0;                 ///< beam axis in the vehicle frame
  std::optional<double> first_hit_range_m;  ///< first surface on the axis, from the head
  std::optional<double> strongest_range_m;  ///< strongest noise-free echo after TVG
  bool strongest_multipath = false;         ///< that echo came by a specular route
  std::string strongest_surface;            ///< material (OBJ group) that returned it
  /// The horizontal angle from the beam's axis to the first surface of the echo that gave the
  /// most to the strongest bin, counter-clockwise seen from above (rad); none when there is no
  /// echo, or in a dataset simulated before this column was written.
  std::optional<double> strongest_bearing_offset_rad;
  bool operator==(const BeamTruthRow& other) const;
};

std::vector<BeamTruthRow> read_beam_truth(const std::string& path);
/// Writes the rows atomically, numbers in the shortest form that reads back exactly (the inverse
/// of read_beam_truth).
void write_beam_truth(const std::string& path, const std::vector<BeamTruthRow>& rows);

}  // namespace msislab::io
