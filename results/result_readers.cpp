#include "results/result_readers.hpp"

#include <algorithm>
#include <array>
#include <string>
#include <string_view>

#include "io/input_error.hpp"
#include "io/ply.hpp"
#include "io/text_lines.hpp"

namespace msislab::results {

std::vector<Eigen::Vector2d> read_points_ply(const std::string& path) {
  std::vector<Eigen::Vector2d> points;
  for (const Eigen::Vector3d& point_m : io::read_ply(path).vertices_m)
    points.push_back(point_m.head<2>());
  return points;
}

std::vector<NeesRow> read_montecarlo_nees(const std::string& path) {
  static constexpr std::array<std::string_view, 6> kNames = {"method",    "scan",  "runs",
                                                             "mean_nees", "lower", "upper"};
  std::vector<NeesRow> rows;
  io::for_each_csv_row(
      path, "method,scan,runs,mean_nees,lower,upper",
      [&](std::string_view line, std::size_t number) {
        const auto f = io::split_csv<kNames.size()>(line, path, number);
        const auto at = [&](std::size_t i) { return io::FieldAt{path, number, i + 1, kNames[i]}; };
        NeesRow row;
        if (f[0].empty()) io::fail_field(at(0), f[0], "is empty");
        row.method = std::string(f[0]);
        row.scan = io::parse_integer(f[1], at(1));
        row.runs = io::parse_integer(f[2], at(2));
        if (row.runs < 1) io::fail_field(at(2), f[2], "is not a positive count");
        row.mean_nees = io::parse_finite(f[3], at(3));
        row.lower = io::parse_finite(f[4], at(4));
        row.upper = io::parse_finite(f[5], at(5));
        for (auto it = rows.rbegin(); it != rows.rend(); ++it) {
          if (it->method != row.method) continue;
          if (row.scan <= it->scan) {
            io::fail_field(at(1), f[1], "does not increase for method " + row.method);
          }
          break;
        }
        rows.push_back(row);
      });
  io::require_data_rows(path, rows.size());
  return rows;
}

std::vector<ErrorSpreadRow> read_error_spread_csv(const std::string& path) {
  static constexpr std::array<std::string_view, 7> kNames = {"method", "t_s",   "runs", "mean_m",
                                                             "p05_m",  "p50_m", "p95_m"};
  std::vector<ErrorSpreadRow> rows;
  io::for_each_csv_row(
      path, "method,t_s,runs,mean_m,p05_m,p50_m,p95_m",
      [&](std::string_view line, std::size_t number) {
        const auto f = io::split_csv<kNames.size()>(line, path, number);
        const auto at = [&](std::size_t i) { return io::FieldAt{path, number, i + 1, kNames[i]}; };
        ErrorSpreadRow row;
        if (f[0].empty()) io::fail_field(at(0), f[0], "is empty");
        row.method = std::string(f[0]);
        row.spread.t_s = io::parse_finite(f[1], at(1));
        const long long runs = io::parse_integer(f[2], at(2));
        if (runs < 1) io::fail_field(at(2), f[2], "is not a positive count");
        row.spread.runs = static_cast<int>(runs);
        row.spread.mean_m = io::parse_finite(f[3], at(3));
        row.spread.p05_m = io::parse_finite(f[4], at(4));
        row.spread.p50_m = io::parse_finite(f[5], at(5));
        row.spread.p95_m = io::parse_finite(f[6], at(6));
        if (!rows.empty() && rows.back().method == row.method &&
            !(row.spread.t_s > rows.back().spread.t_s)) {
          io::fail_field(at(1), f[1], "does not increase for method " + row.method);
        }
        rows.push_back(row);
      });
  return rows;
}

std::vector<ErrorHistogram> read_error_histogram_csv(const std::string& path) {
  static constexpr std::array<std::string_view, 4> kNames = {"method", "lower_m", "upper_m",
                                                             "fraction"};
  std::vector<ErrorHistogram> histograms;
  io::for_each_csv_row(
      path, "method,lower_m,upper_m,fraction", [&](std::string_view line, std::size_t number) {
        const auto f = io::split_csv<kNames.size()>(line, path, number);
        const auto at = [&](std::size_t i) { return io::FieldAt{path, number, i + 1, kNames[i]}; };
        if (f[0].empty()) io::fail_field(at(0), f[0], "is empty");
        const double lower = io::parse_finite(f[1], at(1));
        const double upper = io::parse_finite(f[2], at(2));
        const double fraction = io::parse_finite(f[3], at(3));
        if (!(upper > lower)) io::fail_field(at(2), f[2], "is not above lower_m");
        if (fraction < 0.0 || fraction > 1.0) {
          io::fail_field(at(3), f[3], "is not a fraction in [0, 1]");
        }
        if (histograms.empty() || histograms.back().method != f[0]) {
          histograms.push_back({std::string(f[0]), {lower}, {}});
        } else if (lower != histograms.back().edges_m.back()) {
          io::fail_field(at(1), f[1], "does not continue the previous bin");
        }
        histograms.back().edges_m.push_back(upper);
        histograms.back().fractions.push_back(fraction);
      });
  return histograms;
}

}  // namespace msislab::results
