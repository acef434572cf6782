#include "io/detections.hpp"

#include <array>
#include <limits>
#include <ostream>
#include <string_view>

#include "io/atomic_file.hpp"
#include "io/gzip_stream.hpp"
#include "io/input_error.hpp"
#include "io/text_lines.hpp"

namespace msislab::io {
namespace {

constexpr std::string_view kHeader =
    "keyframe,beam_row,t_log_s,sensor_time_ms,angle_idx,angle_rad,range_m";
constexpr std::array<std::string_view, 7> kNames = {
    "keyframe", "beam_row", "t_log_s", "sensor_time_ms", "angle_idx", "angle_rad", "range_m"};

bool is_gzip_name(const std::string& path) {
  constexpr std::string_view kSuffix = ".gz";
  return path.size() >= kSuffix.size() &&
         path.compare(path.size() - kSuffix.size(), kSuffix.size(), kSuffix) == 0;
}

std::int32_t parse_int32(std::string_view token, const FieldAt& at) {
  const std::int64_t value = parse_integer(token, at);
  if (value < std::numeric_limits<std::int32_t>::min() ||
      value > std::numeric_limits<std::int32_t>::max())
    fail_field(at, token, "is out of range");
  return static_cast<std::int32_t>(value);
}

DetectionRecord parse_row(std::string_view line, std::size_t line_number, const std::string& path) {
  const std::array<std::string_view, 7> f = split_csv<7>(line, path, line_number);
  const auto at = [&](std::size_t i) { return FieldAt{path, line_number, i + 1, kNames[i]}; };
  DetectionRecord r;
  r.keyframe = parse_int32(f[0], at(0));
  r.beam_row = parse_integer(f[1], at(1));
  r.t_log_s = parse_finite(f[2], at(2));
  r.sensor_time_ms = parse_integer(f[3], at(3));
  r.angle_idx = parse_int32(f[4], at(4));
  r.angle_rad = parse_finite(f[5], at(5));
  r.range_m = parse_finite(f[6], at(6));
  return r;
}

void append_row(std::string& out, const DetectionRecord& r, const std::string& path,
                std::size_t row) {
  out += std::to_string(r.keyframe);
  out += ',';
  out += std::to_string(r.beam_row);
  out += ',';
  append_finite(out, r.t_log_s, path, row, "t_log_s");
  out += ',';
  out += std::to_string(r.sensor_time_ms);
  out += ',';
  out += std::to_string(r.angle_idx);
  out += ',';
  append_finite(out, r.angle_rad, path, row, "angle_rad");
  out += ',';
  append_finite(out, r.range_m, path, row, "range_m");
  out += '\n';
}

void check_beam_order(const std::string& path, const std::vector<DetectionRecord>& rows) {
  for (std::size_t row = 1; row < rows.size(); ++row)
    if (rows[row].beam_row < rows[row - 1].beam_row)
      fail_file(path, "row " + std::to_string(row + 1) + ": beam_row goes backwards (" +
                          std::to_string(rows[row].beam_row) + " after " +
                          std::to_string(rows[row - 1].beam_row) + "), cannot write it");
}

}  // namespace

bool DetectionRecord::operator==(const DetectionRecord& other) const {
  return keyframe == other.keyframe && beam_row == other.beam_row && t_log_s == other.t_log_s &&
         sensor_time_ms == other.sensor_time_ms && angle_idx == other.angle_idx &&
         angle_rad == other.angle_rad && range_m == other.range_m;
}

// The header, then one record per non-blank line in beam_row order; .csv and .csv.gz alike.
std::vector<DetectionRecord> read_detections(const std::string& path) {
  std::vector<DetectionRecord> rows;
  for_each_csv_row(path, kHeader, [&](std::string_view line, std::size_t line_number) {
    const DetectionRecord record = parse_row(line, line_number, path);
    if (!rows.empty() && record.beam_row < rows.back().beam_row)
      fail_at(path, line_number,
              "beam_row goes backwards (" + std::to_string(record.beam_row) + " after " +
                  std::to_string(rows.back().beam_row) + ")");
    rows.push_back(record);
  });
  require_data_rows(path, rows.size());
  return rows;
}

void write_detections(const std::string& path, const std::vector<DetectionRecord>& rows) {
  check_beam_order(path, rows);
  write_file_atomically(path, [&](std::ostream& out) {
    GzipStream gzip(out, path, is_gzip_name(path));
    std::string text(kHeader);
    text += '\n';
    constexpr std::size_t kFlushBytes = std::size_t{1} << 20;
    for (std::size_t row = 0; row < rows.size(); ++row) {
      append_row(text, rows[row], path, row + 1);
      if (text.size() < kFlushBytes) continue;
      gzip.write(text);
      text.clear();
    }
    gzip.write(text);
    gzip.finish();
  });
}

}  // namespace msislab::io
