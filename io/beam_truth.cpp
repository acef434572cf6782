#include "io/beam_truth.hpp"

#include <algorithm>
#include <array>
#include <fstream>
#include <string>
#include <string_view>

#include "io/atomic_file.hpp"
#include "io/input_error.hpp"
#include "io/text_lines.hpp"

namespace msislab::io {
namespace {

constexpr std::string_view kBeamTruthHeader =
    "t_s,x_m,y_m,yaw_rad,bearing_rad,first_hit_range_m,strongest_range_m,strongest_multipath,"
    "strongest_surface,strongest_bearing_offset_rad";
/// The header of datasets simulated before the strongest echo's bearing was written (read with
/// that column empty).
constexpr std::string_view kBeamTruthHeaderWithoutBearing =
    "t_s,x_m,y_m,yaw_rad,bearing_rad,first_hit_range_m,strongest_range_m,strongest_multipath,"
    "strongest_surface";
constexpr std::array<std::string_view, 10> kBeamTruthNames = {"t_s",
                                                              "x_m",
                                                              "y_m",
                                                              "yaw_rad",
                                                              "bearing_rad",
                                                              "first_hit_range_m",
                                                              "strongest_range_m",
                                                              "strongest_multipath",
                                                              "strongest_surface",
                                                              "strongest_bearing_offset_rad"};
using BeamTruthFields = std::array<std::string_view, kBeamTruthNames.size()>;

std::optional<double> parse_optional(std::string_view token, const FieldAt& at) {
  if (token.empty()) return std::nullopt;
  return parse_finite(token, at);
}

bool parse_flag(std::string_view token, const FieldAt& at) {
  if (token != "0" && token != "1") fail_field(at, token, "is not 0 or 1");
  return token == "1";
}

BeamTruthRow parse_beam_truth_row(std::string_view line, std::size_t line_number,
                                  const std::string& path, bool with_bearing) {
  BeamTruthFields f;
  split_csv_fields(line, path, line_number, f.data(), with_bearing ? f.size() : f.size() - 1);
  const auto at = [&](std::size_t i) {
    return FieldAt{path, line_number, i + 1, kBeamTruthNames[i]};
  };
  BeamTruthRow row;
  row.t_s = parse_finite(f[0], at(0));
  row.x_m = parse_finite(f[1], at(1));
  row.y_m = parse_finite(f[2], at(2));
  row.yaw_rad = parse_finite(f[3], at(3));
  row.bearing_rad = parse_finite(f[4], at(4));
  row.first_hit_range_m = parse_optional(f[5], at(5));
  row.strongest_range_m = parse_optional(f[6], at(6));
  row.strongest_multipath = parse_flag(f[7], at(7));
  row.strongest_surface = std::string(f[8]);
  if (with_bearing) row.strongest_bearing_offset_rad = parse_optional(f[9], at(9));
  return row;
}

}  // namespace

bool BeamTruthRow::operator==(const BeamTruthRow& other) const {
  return t_s == other.t_s && x_m == other.x_m && y_m == other.y_m && yaw_rad == other.yaw_rad &&
         bearing_rad == other.bearing_rad && first_hit_range_m == other.first_hit_range_m &&
         strongest_range_m == other.strongest_range_m &&
         strongest_multipath == other.strongest_multipath &&
         strongest_surface == other.strongest_surface &&
         strongest_bearing_offset_rad == other.strongest_bearing_offset_rad;
}

void write_beam_truth(const std::string& path, const std::vector<BeamTruthRow>& rows) {
  write_file_atomically(path, [&](std::ostream& out) {
    std::string text = std::string(kBeamTruthHeader) + "\n";
    for (const BeamTruthRow& r : rows) {
      for (const double v : {r.t_s, r.x_m, r.y_m, r.yaw_rad, r.bearing_rad}) {
        append_number(text, v);
        text += ',';
      }
      for (const std::optional<double>& range : {r.first_hit_range_m, r.strongest_range_m}) {
        if (range) text += format_number(*range);
        text += ',';
      }
      text += std::string(r.strongest_multipath ? "1" : "0") + "," + r.strongest_surface + ",";
      if (r.strongest_bearing_offset_rad) text += format_number(*r.strongest_bearing_offset_rad);
      text += '\n';
    }
    out << text;
  });
}

std::vector<BeamTruthRow> read_beam_truth(const std::string& path) {
  std::vector<BeamTruthRow> rows;
  // A dataset simulated before the bearing column was written is read without it.
  std::string first_line;
  {
    std::ifstream in(path);
    std::getline(in, first_line);
    if (!first_line.empty() && first_line.back() == '\r') first_line.pop_back();
  }
  const bool with_bearing = first_line != kBeamTruthHeaderWithoutBearing;
  const std::string_view header = with_bearing ? kBeamTruthHeader : kBeamTruthHeaderWithoutBearing;
  for_each_csv_row(path, header, [&](std::string_view line, std::size_t line_number) {
    rows.push_back(parse_beam_truth_row(line, line_number, path, with_bearing));
    if (rows.size() > 1 && rows.back().t_s < rows[rows.size() - 2].t_s) {
      fail_at(path, line_number,
              "t_s goes backwards (" + format_number(rows.back().t_s) + " after " +
                  format_number(rows[rows.size() - 2].t_s) + ")");
    }
  });
  require_data_rows(path, rows.size());
  return rows;
}

}  // namespace msislab::io
