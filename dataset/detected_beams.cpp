#include "dataset/detected_beams.hpp"

#include <cmath>
#include <string>

#include "io/input_error.hpp"
#include "io/text_lines.hpp"

namespace msislab::dataset {

namespace {

[[noreturn]] void fail_row(const std::string& path, std::size_t index, const io::DetectionRecord& r,
                           const std::string& what) {
  io::fail_file(path, "data row " + std::to_string(index + 1) + " (beam_row " +
                          std::to_string(r.beam_row) + "): " + what);
}

void check_row(const std::string& path, std::size_t index, const io::DetectionRecord& r,
               std::size_t beam_count, double max_range_m) {
  if (r.beam_row < 0 || static_cast<std::size_t>(r.beam_row) >= beam_count) {
    fail_row(path, index, r,
             "not a row of the beam times (" + std::to_string(beam_count) + " beams)");
  }
  if (!(r.range_m >= 0.0 && r.range_m <= max_range_m)) {
    fail_row(path, index, r,
             "range_m " + io::format_number(r.range_m) + " outside the sonar range 0.." +
                 io::format_number(max_range_m) + " m");
  }
}

/// Checks that row r continues the beam (same keyframe and angle) or starts a new one after it.
void check_continuation(const std::string& path, std::size_t index, const io::DetectionRecord& r,
                        const DetectedBeam& beam) {
  if (r.keyframe < beam.keyframe) {
    fail_row(path, index, r,
             "keyframe " + std::to_string(r.keyframe) + " after keyframe " +
                 std::to_string(beam.keyframe));
  }
  if (r.beam_row == beam.beam_row &&
      (r.keyframe != beam.keyframe || r.angle_idx != beam.angle_idx)) {
    fail_row(path, index, r, "keyframe or angle_idx differs from the beam's earlier rows");
  }
}

void check_keyframe_span(const std::string& path, const std::vector<DetectedBeam>& beams,
                         int beams_per_revolution) {
  std::size_t first = 0;
  for (std::size_t i = 1; i <= beams.size(); ++i) {
    if (i < beams.size() && beams[i].keyframe == beams[first].keyframe) continue;
    const std::int64_t span = beams[i - 1].beam_row - beams[first].beam_row + 1;
    if (span > beams_per_revolution) {
      io::fail_file(path, "keyframe " + std::to_string(beams[first].keyframe) +
                              " spans beam rows " + std::to_string(beams[first].beam_row) + ".." +
                              std::to_string(beams[i - 1].beam_row) +
                              ", more than one revolution of " +
                              std::to_string(beams_per_revolution) + " beams");
    }
    first = i;
  }
}

}  // namespace

std::vector<DetectedBeam> group_detections(const std::vector<io::DetectionRecord>& rows,
                                           const std::string& path, std::size_t beam_count,
                                           int beams_per_revolution, double max_range_m) {
  std::vector<DetectedBeam> beams;
  for (std::size_t i = 0; i < rows.size(); ++i) {
    const io::DetectionRecord& r = rows[i];
    check_row(path, i, r, beam_count, max_range_m);
    if (!beams.empty()) check_continuation(path, i, r, beams.back());
    if (beams.empty() || beams.back().beam_row != r.beam_row) {
      beams.push_back({r.beam_row, r.keyframe, r.angle_idx, r.angle_rad, {}});
    }
    beams.back().ranges_m.push_back(r.range_m);
  }
  check_keyframe_span(path, beams, beams_per_revolution);
  if (!beams.empty()) {
    const std::int64_t counted =
        (std::int64_t{beams.back().keyframe} - beams.front().keyframe + 1) * beams_per_revolution;
    if (counted > static_cast<std::int64_t>(beam_count)) {
      io::fail_file(path,
                    "keyframes " + std::to_string(beams.front().keyframe) + ".." +
                        std::to_string(beams.back().keyframe) + " make " + std::to_string(counted) +
                        " beams of " + std::to_string(beams_per_revolution) +
                        " per revolution, but the beam times have " + std::to_string(beam_count));
    }
  }
  return beams;
}

}  // namespace msislab::dataset
