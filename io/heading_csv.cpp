#include "io/heading_csv.hpp"

#include "io/atomic_file.hpp"
#include "io/input_error.hpp"
#include "io/text_lines.hpp"

namespace msislab::io {

std::vector<Eigen::Vector2d> read_heading_csv(const std::string& path) {
  std::vector<Eigen::Vector2d> rows;
  for_each_csv_row(path, kHeadingCsvHeader, [&](std::string_view line, std::size_t number) {
    const auto f = split_csv<2>(line, path, number);
    const double t_s = parse_finite(f[0], FieldAt{path, number, 1, "t_s"});
    const double yaw_deg = parse_finite(f[1], FieldAt{path, number, 2, "yaw_deg"});
    if (!rows.empty() && !(t_s > rows.back().x())) {
      fail_at(path, number,
              "time does not increase (" + format_number(t_s) + " after " +
                  format_number(rows.back().x()) + ")");
    }
    rows.emplace_back(t_s, yaw_deg);
  });
  if (rows.size() < 2) fail_file(path, "needs at least two rows of t_s,yaw_deg");
  return rows;
}

void write_heading_csv(const std::string& path, const std::vector<Eigen::Vector2d>& rows) {
  write_file_atomically(path, [&](std::ostream& out) {
    out << kHeadingCsvHeader << "\n";
    std::string line;
    for (const Eigen::Vector2d& r : rows) {
      line.clear();
      append_number(line, r.x());
      line += ',';
      append_number(line, r.y());
      out << line << "\n";
    }
  });
}

}  // namespace msislab::io
