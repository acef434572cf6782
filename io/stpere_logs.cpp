#include "io/stpere_logs.hpp"

#include <array>
#include <cmath>
#include <ostream>
#include <string_view>
#include <vector>

#include "io/atomic_file.hpp"
#include "io/input_error.hpp"
#include "io/stpere_columns.hpp"
#include "io/text_lines.hpp"

namespace msislab::io {
namespace {

// The [idSensor] column, when filled, is the token right after logTime; it is not kept.
template <typename Format>
bool has_id_sensor(const DataLines& lines) {
  if (Format::kOptionalIdSensor && lines.size() == Format::kNames.size() + 1) return true;
  lines.expect_columns(Format::kNames.size());
  return false;
}

template <typename Format, typename Record>
std::vector<Record> read_columns_log(const std::string& path) {
  DataLines lines(path);
  std::vector<Record> rows;
  while (lines.next()) {
    const bool skip_id = has_id_sensor<Format>(lines);
    Record record;
    std::size_t column = 0;
    Format::visit(record, [&](double& value) {
      const std::size_t token = (skip_id && column > 0) ? column + 1 : column;
      value = lines.number(token, Format::kNames[column]);
      ++column;
    });
    if (!rows.empty()) check_time_order(lines, rows.back().t_log_s, record.t_log_s);
    rows.push_back(record);
  }
  require_data_rows(path, rows.size());
  return rows;
}

template <typename Format, typename Record>
void write_columns_log(const std::string& path, const std::vector<Record>& rows) {
  write_file_atomically(path, [&](std::ostream& out) {
    out << Format::kHeader;
    std::string line;
    for (std::size_t row = 0; row < rows.size(); ++row) {
      line.clear();
      std::size_t column = 0;
      Format::visit(rows[row], [&](double value) {
        line += Format::kSeparatorBefore[column];
        append_finite(line, value, path, row + 1, Format::kNames[column]);
        ++column;
      });
      line += Format::kLineEnd;
      line += '\n';
      out.write(line.data(), static_cast<std::streamsize>(line.size()));
    }
  });
}

// Memberwise and exact, in column order.
template <typename Format, typename Record>
bool same_columns(const Record& a, const Record& b) {
  std::array<double, Format::kNames.size()> columns_a{};
  std::array<double, Format::kNames.size()> columns_b{};
  std::size_t i = 0;
  Format::visit(a, [&](double value) { columns_a[i++] = value; });
  i = 0;
  Format::visit(b, [&](double value) { columns_b[i++] = value; });
  return columns_a == columns_b;
}

}  // namespace

bool DvlRecord::operator==(const DvlRecord& other) const {
  return same_columns<DvlFormat>(*this, other);
}
bool MtiRecord::operator==(const MtiRecord& other) const {
  return same_columns<MtiFormat>(*this, other);
}
bool GpsRecord::operator==(const GpsRecord& other) const {
  return same_columns<GpsFormat>(*this, other);
}
bool BeamTimeRecord::operator==(const BeamTimeRecord& other) const {
  return same_columns<BeamTimeFormat>(*this, other);
}
bool SonarSetup::operator==(const SonarSetup& other) const {
  return range_m == other.range_m && bin_m == other.bin_m && step_rad == other.step_rad;
}

// ddmm.mmmm: the hundreds and above are whole degrees, the rest minutes.
double nmea_to_degrees(double ddmm) {
  const double magnitude = std::abs(ddmm);
  const double degrees = std::floor(magnitude / 100.0);
  const double minutes = magnitude - 100.0 * degrees;
  return std::copysign(degrees + minutes / 60.0, ddmm);
}

double degrees_to_nmea(double degrees) {
  const double magnitude = std::abs(degrees);
  const double whole = std::floor(magnitude);
  return std::copysign(100.0 * whole + 60.0 * (magnitude - whole), degrees);
}

std::vector<DvlRecord> read_dvl_log(const std::string& path) {
  return read_columns_log<DvlFormat, DvlRecord>(path);
}
void write_dvl_log(const std::string& path, const std::vector<DvlRecord>& rows) {
  write_columns_log<DvlFormat>(path, rows);
}

std::vector<MtiRecord> read_mti_log(const std::string& path) {
  return read_columns_log<MtiFormat, MtiRecord>(path);
}
void write_mti_log(const std::string& path, const std::vector<MtiRecord>& rows) {
  write_columns_log<MtiFormat>(path, rows);
}

std::vector<GpsRecord> read_gps_log(const std::string& path) {
  return read_columns_log<GpsFormat, GpsRecord>(path);
}
void write_gps_log(const std::string& path, const std::vector<GpsRecord>& rows) {
  write_columns_log<GpsFormat>(path, rows);
}

std::vector<BeamTimeRecord> read_beam_times_log(const std::string& path) {
  return read_columns_log<BeamTimeFormat, BeamTimeRecord>(path);
}
void write_beam_times_log(const std::string& path, const std::vector<BeamTimeRecord>& rows) {
  write_columns_log<BeamTimeFormat>(path, rows);
}

int steps_per_revolution(const SonarSetup& setup) {
  return static_cast<int>(std::lround(2.0 * M_PI / setup.step_rad));
}

SonarSetup read_setup_log(const std::string& path) {
  DataLines lines(path);
  if (!lines.next()) require_data_rows(path, 0);
  lines.expect_columns(3);
  SonarSetup setup;
  setup.range_m = lines.number(0, "range_m");
  setup.bin_m = lines.number(1, "bin_m");
  setup.step_rad = lines.number(2, "step_rad");
  // A zero or negative size would make every later bin and step computation meaningless.
  if (!(setup.range_m > 0.0 && setup.bin_m > 0.0 && setup.step_rad > 0.0))
    lines.fail("range_m, bin_m and step_rad must be positive");
  if (lines.next()) lines.fail("extra data row: the setup log has exactly one row");
  return setup;
}

void write_setup_log(const std::string& path, const SonarSetup& setup) {
  write_file_atomically(path, [&](std::ostream& out) {
    std::string line;
    append_finite(line, setup.range_m, path, 1, "range_m");
    line += ' ';
    append_finite(line, setup.bin_m, path, 1, "bin_m");
    line += ' ';
    append_finite(line, setup.step_rad, path, 1, "step_rad");
    line += '\n';
    out << line;
  });
}

}  // namespace msislab::io
