// The raw imaging sonar log (*_IS.log) of stpere_logs.hpp: one beam per row, "logTime_s
// sensorTime_ms transducerAngle_rad bin1 ... binN" with integer intensities 0..255.
#include "io/stpere_logs.hpp"

#include <charconv>
#include <cstdint>
#include <ostream>
#include <string>
#include <system_error>
#include <vector>

#include "io/atomic_file.hpp"
#include "io/input_error.hpp"
#include "io/text_lines.hpp"

namespace msislab::io {
namespace {

// Bins are the hot loop of the largest log (46,000 beams x 500 bins), so they are parsed in place.
std::uint8_t parse_bin(const DataLines& lines, std::size_t token) {
  const std::string_view text = lines.field(token);
  const char* end = text.data() + text.size();
  int value = -1;
  const auto [ptr, ec] = std::from_chars(text.data(), end, value);
  if (ec == std::errc() && ptr == end && value >= 0 && value <= 255)
    return static_cast<std::uint8_t>(value);
  const bool integer = ptr == end && (ec == std::errc() || ec == std::errc::result_out_of_range);
  const std::string column = "bin " + std::to_string(token - 2);
  fail_field(FieldAt{lines.path(), lines.line_number(), token + 1, column}, text,
             integer ? "is out of range 0..255" : "is not an integer 0..255");
}

// Every beam must have the bin count of the first, or a bin index would mean different ranges.
std::size_t check_bin_count(const DataLines& lines, std::size_t bins, std::size_t first_line) {
  const std::size_t got = lines.size();
  if (bins == 0) {
    if (got < 4)
      lines.fail(
          "truncated line: expected at least 4 columns (logTime, sensorTime, angle, bins), "
          "got " +
          std::to_string(got));
    return got - 3;
  }
  if (got != 3 + bins)
    lines.fail(column_count_error(3 + bins, got) + ": every beam needs " + std::to_string(bins) +
               " bins, as on line " + std::to_string(first_line));
  return bins;
}

SonarBeamRecord read_beam(const DataLines& lines, std::size_t bins) {
  SonarBeamRecord beam;
  beam.t_log_s = lines.number(0, "logTime");
  beam.sensor_time_ms = lines.number(1, "sensorTime");
  beam.transducer_angle_rad = lines.number(2, "transducerAngle");
  beam.intensity.resize(bins);
  for (std::size_t i = 0; i < bins; ++i) beam.intensity[i] = parse_bin(lines, 3 + i);
  return beam;
}

void check_same_bin_counts(const std::string& path, const std::vector<SonarBeamRecord>& rows) {
  for (std::size_t row = 0; row < rows.size(); ++row) {
    const std::size_t bins = rows[row].intensity.size();
    if (bins == 0 || bins != rows.front().intensity.size())
      fail_file(path, "row " + std::to_string(row + 1) + ": " + std::to_string(bins) +
                          " bins, but every beam needs the same bin count (at least 1) as row 1 (" +
                          std::to_string(rows.front().intensity.size()) + ")");
  }
}

std::string is_log_header(std::size_t bins) {
  const std::string n = std::to_string(bins);
  return "% ---------------------------------------\n"
         "% Mechanically scanned imaging sonar, raw beams (one row per beam)\n"
         "% Data columns: \n"
         "% logTime (s), sensorTime (ms), transducerAngle (rad), bin1, ..., bin" +
         n +
         "\n"
         "% bin i: echo intensity 0..255 at range i x bin size (see *_SETUP.log)\n"
         "% bins per beam: " +
         n +
         "\n"
         "% written by msislab\n"
         "% ---------------------------------------\n";
}

void append_beam(std::string& line, const SonarBeamRecord& beam, const std::string& path,
                 std::size_t row) {
  append_finite(line, beam.t_log_s, path, row, "logTime");
  line += ' ';
  append_finite(line, beam.sensor_time_ms, path, row, "sensorTime");
  line += ' ';
  append_finite(line, beam.transducer_angle_rad, path, row, "transducerAngle");
  char digits[4];
  for (const std::uint8_t bin : beam.intensity) {
    line += ' ';
    line.append(digits, std::to_chars(digits, digits + sizeof(digits), bin).ptr);
  }
  line += '\n';
}

}  // namespace

bool SonarBeamRecord::operator==(const SonarBeamRecord& other) const {
  return t_log_s == other.t_log_s && sensor_time_ms == other.sensor_time_ms &&
         transducer_angle_rad == other.transducer_angle_rad && intensity == other.intensity;
}

std::vector<SonarBeamRecord> read_is_log(const std::string& path) {
  DataLines lines(path);
  std::vector<SonarBeamRecord> rows;
  std::size_t bins = 0;
  std::size_t first_line = 0;
  while (lines.next()) {
    if (rows.empty()) first_line = lines.line_number();
    bins = check_bin_count(lines, bins, first_line);
    SonarBeamRecord beam = read_beam(lines, bins);
    if (!rows.empty()) check_time_order(lines, rows.back().t_log_s, beam.t_log_s);
    rows.push_back(std::move(beam));
  }
  require_data_rows(path, rows.size());
  return rows;
}

void write_is_log(const std::string& path, const std::vector<SonarBeamRecord>& rows) {
  check_same_bin_counts(path, rows);
  write_file_atomically(path, [&](std::ostream& out) {
    out << is_log_header(rows.empty() ? 0 : rows.front().intensity.size());
    std::string line;
    for (std::size_t row = 0; row < rows.size(); ++row) {
      line.clear();
      append_beam(line, rows[row], path, row + 1);
      out.write(line.data(), static_cast<std::streamsize>(line.size()));
    }
  });
}

}  // namespace msislab::io
