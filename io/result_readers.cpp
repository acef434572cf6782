#include "io/result_readers.hpp"

#include <algorithm>
#include <array>
#include <string>
#include <string_view>

#include "io/input_error.hpp"
#include "io/text_lines.hpp"

namespace msislab::io {
namespace {

/// Lines of a text file, numbered from 1, without their '\r'.
class TextLines {
 public:
  explicit TextLines(const std::string& path) : path_(path), text_(read_whole_file(path)) {}
  bool next(std::string_view& line) {
    if (offset_ >= text_.size()) return false;
    const std::size_t newline = std::min(text_.find('\n', offset_), text_.size());
    line = strip_cr(std::string_view(text_).substr(offset_, newline - offset_));
    offset_ = newline + 1;
    ++number_;
    return true;
  }
  std::size_t number() const { return number_; }
  const std::string& path() const { return path_; }

 private:
  const std::string& path_;
  std::string text_;
  std::size_t offset_ = 0;
  std::size_t number_ = 0;
};

std::vector<std::string_view> split_blanks(std::string_view line) {
  std::vector<std::string_view> fields;
  std::size_t i = 0;
  while (i < line.size()) {
    while (i < line.size() && (line[i] == ' ' || line[i] == '\t')) ++i;
    const std::size_t start = i;
    while (i < line.size() && line[i] != ' ' && line[i] != '\t') ++i;
    if (i > start) fields.push_back(line.substr(start, i - start));
  }
  return fields;
}

/// The PLY header up to end_header: the vertex count and the columns of x and y.
struct PlyLayout {
  long long vertices = -1;
  std::size_t properties = 0;
  std::size_t x = 0, y = 0;
  bool has_x = false, has_y = false;
};

PlyLayout read_ply_header(TextLines& lines) {
  std::string_view line;
  if (!lines.next(line) || line != "ply") {
    fail_file(lines.path(), "not a PLY file (the first line is not 'ply')");
  }
  PlyLayout layout;
  bool in_vertex = false;
  while (lines.next(line)) {
    const std::vector<std::string_view> f = split_blanks(line);
    if (f.empty() || f[0] == "comment" || f[0] == "obj_info") continue;
    if (f[0] == "end_header") {
      if (layout.vertices < 0 || !layout.has_x || !layout.has_y) {
        fail_at(lines.path(), lines.number(), "no 'element vertex' with x and y properties");
      }
      return layout;
    }
    if (f[0] == "format" && (f.size() < 2 || f[1] != "ascii")) {
      fail_at(lines.path(), lines.number(),
              "only ASCII PLY is read here, got '" + std::string(line) + "'");
    }
    if (f[0] == "element") {
      in_vertex = f.size() == 3 && f[1] == "vertex" && layout.vertices < 0;
      if (in_vertex) layout.vertices = parse_integer(f[2], {lines.path(), lines.number(), 3, "N"});
      if (layout.vertices < 0) fail_at(lines.path(), lines.number(), "vertex must come first");
    }
    if (f[0] == "property" && in_vertex) {
      if (f.size() != 3) fail_at(lines.path(), lines.number(), "list properties are not read");
      if (f[2] == "x") {
        layout.x = layout.properties;
        layout.has_x = true;
      }
      if (f[2] == "y") {
        layout.y = layout.properties;
        layout.has_y = true;
      }
      ++layout.properties;
    }
  }
  fail_file(lines.path(), "no end_header line");
}

}  // namespace

std::vector<Eigen::Vector2d> read_points_ply(const std::string& path) {
  TextLines lines(path);
  const PlyLayout layout = read_ply_header(lines);
  std::vector<Eigen::Vector2d> points;
  points.reserve(static_cast<std::size_t>(layout.vertices));
  std::string_view line;
  while (static_cast<long long>(points.size()) < layout.vertices && lines.next(line)) {
    const std::vector<std::string_view> f = split_blanks(line);
    if (f.size() != layout.properties) {
      fail_at(path, lines.number(), column_count_error(layout.properties, f.size()));
    }
    points.emplace_back(parse_finite(f[layout.x], {path, lines.number(), layout.x + 1, "x"}),
                        parse_finite(f[layout.y], {path, lines.number(), layout.y + 1, "y"}));
  }
  if (static_cast<long long>(points.size()) < layout.vertices) {
    fail_file(path, "truncated: the header announces " + std::to_string(layout.vertices) +
                        " vertices, the file has " + std::to_string(points.size()));
  }
  return points;
}

std::vector<NeesRow> read_montecarlo_nees(const std::string& path) {
  static constexpr std::array<std::string_view, 6> kNames = {"method",    "scan",  "runs",
                                                             "mean_nees", "lower", "upper"};
  std::vector<NeesRow> rows;
  for_each_csv_row(path, "method,scan,runs,mean_nees,lower,upper",
                   [&](std::string_view line, std::size_t number) {
                     const auto f = split_csv<kNames.size()>(line, path, number);
                     const auto at = [&](std::size_t i) {
                       return FieldAt{path, number, i + 1, kNames[i]};
                     };
                     NeesRow row;
                     if (f[0].empty()) fail_field(at(0), f[0], "is empty");
                     row.method = std::string(f[0]);
                     row.scan = parse_integer(f[1], at(1));
                     row.runs = parse_integer(f[2], at(2));
                     if (row.runs < 1) fail_field(at(2), f[2], "is not a positive count");
                     row.mean_nees = parse_finite(f[3], at(3));
                     row.lower = parse_finite(f[4], at(4));
                     row.upper = parse_finite(f[5], at(5));
                     for (auto it = rows.rbegin(); it != rows.rend(); ++it) {
                       if (it->method != row.method) continue;
                       if (row.scan <= it->scan) {
                         fail_field(at(1), f[1], "does not increase for method " + row.method);
                       }
                       break;
                     }
                     rows.push_back(row);
                   });
  require_data_rows(path, rows.size());
  return rows;
}

std::vector<ErrorSpreadRow> read_error_spread_csv(const std::string& path) {
  static constexpr std::array<std::string_view, 7> kNames = {"method", "t_s",   "runs", "mean_m",
                                                             "p05_m",  "p50_m", "p95_m"};
  std::vector<ErrorSpreadRow> rows;
  for_each_csv_row(path, "method,t_s,runs,mean_m,p05_m,p50_m,p95_m",
                   [&](std::string_view line, std::size_t number) {
                     const auto f = split_csv<kNames.size()>(line, path, number);
                     const auto at = [&](std::size_t i) {
                       return FieldAt{path, number, i + 1, kNames[i]};
                     };
                     ErrorSpreadRow row;
                     if (f[0].empty()) fail_field(at(0), f[0], "is empty");
                     row.method = std::string(f[0]);
                     row.spread.t_s = parse_finite(f[1], at(1));
                     const long long runs = parse_integer(f[2], at(2));
                     if (runs < 1) fail_field(at(2), f[2], "is not a positive count");
                     row.spread.runs = static_cast<int>(runs);
                     row.spread.mean_m = parse_finite(f[3], at(3));
                     row.spread.p05_m = parse_finite(f[4], at(4));
                     row.spread.p50_m = parse_finite(f[5], at(5));
                     row.spread.p95_m = parse_finite(f[6], at(6));
                     if (!rows.empty() && rows.back().method == row.method &&
                         !(row.spread.t_s > rows.back().spread.t_s)) {
                       fail_field(at(1), f[1], "does not increase for method " + row.method);
                     }
                     rows.push_back(row);
                   });
  return rows;
}

std::vector<ErrorHistogram> read_error_histogram_csv(const std::string& path) {
  static constexpr std::array<std::string_view, 4> kNames = {"method", "lower_m", "upper_m",
                                                             "fraction"};
  std::vector<ErrorHistogram> histograms;
  for_each_csv_row(
      path, "method,lower_m,upper_m,fraction", [&](std::string_view line, std::size_t number) {
        const auto f = split_csv<kNames.size()>(line, path, number);
        const auto at = [&](std::size_t i) { return FieldAt{path, number, i + 1, kNames[i]}; };
        if (f[0].empty()) fail_field(at(0), f[0], "is empty");
        const double lower = parse_finite(f[1], at(1));
        const double upper = parse_finite(f[2], at(2));
        const double fraction = parse_finite(f[3], at(3));
        if (!(upper > lower)) fail_field(at(2), f[2], "is not above lower_m");
        if (fraction < 0.0 || fraction > 1.0) {
          fail_field(at(3), f[3], "is not a fraction in [0, 1]");
        }
        if (histograms.empty() || histograms.back().method != f[0]) {
          histograms.push_back({std::string(f[0]), {lower}, {}});
        } else if (lower != histograms.back().edges_m.back()) {
          fail_field(at(1), f[1], "does not continue the previous bin");
        }
        histograms.back().edges_m.push_back(upper);
        histograms.back().fractions.push_back(fraction);
      });
  return histograms;
}

}  // namespace msislab::io
