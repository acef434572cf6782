#include "results/sweep_files.hpp"

#include <algorithm>

#include "io/atomic_file.hpp"
#include "io/input_error.hpp"
#include "io/text_lines.hpp"

namespace msislab::results {

namespace {

constexpr const char* kFigureColumns =
    "method,runs,failed,mean_error_m,mean_error_p05_m,mean_error_p50_m,mean_error_p95_m,anees,"
    "nees_in_bounds_fraction,paired_reference,paired_difference_m,paired_ci95_lower_m,"
    "paired_ci95_upper_m,paired_runs_lower,linearisation_observation,linearisation_inversion,"
    "linearisation_pose";
constexpr std::size_t kFigureCount = 17;

std::string header_of(const std::vector<std::string>& keys) {
  std::string header = "cell";
  for (const std::string& k : keys) header += "," + k;
  return header + "," + kFigureColumns;
}

/// A value's text in a CSV field: its commas become semicolons.
std::string field_text(std::string text) {
  std::replace(text.begin(), text.end(), ',', ';');
  return text;
}

void append_optional(std::string& out, const std::optional<double>& v) {
  out += ',';
  if (v) io::append_number(out, *v);
}

/// The first line of the file (InputError for an empty file).
std::string header_line(const std::string& path) {
  io::LineReader lines(path);
  std::string_view line;
  if (!lines.next(line)) io::fail_file(path, "empty file: no header line");
  return std::string(line);
}

/// The columns of the header line `first`, which must be "cell,<swept keys>,<figures>".
std::vector<std::string> header_columns(const std::string& path, const std::string& first) {
  std::vector<std::string> columns;
  std::size_t start = 0;
  for (std::size_t comma; (comma = first.find(',', start)) != std::string::npos;
       start = comma + 1) {
    columns.push_back(first.substr(start, comma - start));
  }
  columns.push_back(first.substr(start));
  if (columns.size() < 1 + kFigureCount || columns.front() != "cell" ||
      header_of(std::vector<std::string>(columns.begin() + 1, columns.end() - kFigureCount)) !=
          first) {
    io::fail_at(path, 1,
                "wrong header: expected 'cell,<swept keys>," + std::string(kFigureColumns) + "'");
  }
  return columns;
}

/// One row of sweep.csv, its fields f (one per column), with k swept keys; line `number`.
SweepRow parse_row(const std::vector<std::string_view>& f, std::size_t k,
                   const std::vector<std::string>& columns, const std::string& path,
                   std::size_t number) {
  const auto at = [&](std::size_t i) { return io::FieldAt{path, number, i + 1, columns[i]}; };
  const auto optional = [&](std::size_t i) -> std::optional<double> {
    if (f[i].empty()) return std::nullopt;
    return io::parse_finite(f[i], at(i));
  };
  SweepRow r;
  const std::int64_t cell = io::parse_integer(f[0], at(0));
  if (cell < 0) io::fail_field(at(0), f[0], "is not a cell index");
  r.cell = static_cast<int>(cell);
  for (std::size_t i = 0; i < k; ++i) r.values.emplace_back(f[1 + i]);
  if (f[1 + k].empty()) io::fail_field(at(1 + k), f[1 + k], "is empty");
  r.method = std::string(f[1 + k]);
  r.runs = static_cast<int>(io::parse_integer(f[2 + k], at(2 + k)));
  r.failed = static_cast<int>(io::parse_integer(f[3 + k], at(3 + k)));
  r.mean_error_m = optional(4 + k);
  r.p05_m = optional(5 + k);
  r.p50_m = optional(6 + k);
  r.p95_m = optional(7 + k);
  r.anees = optional(8 + k);
  r.nees_in_bounds_fraction = optional(9 + k);
  r.paired_reference = std::string(f[10 + k]);
  r.paired_difference_m = optional(11 + k);
  r.paired_ci95_lower_m = optional(12 + k);
  r.paired_ci95_upper_m = optional(13 + k);
  if (!f[14 + k].empty()) {
    const std::int64_t lower = io::parse_integer(f[14 + k], at(14 + k));
    if (lower < 0) io::fail_field(at(14 + k), f[14 + k], "is not a run count");
    r.paired_runs_lower = static_cast<int>(lower);
  }
  r.linearisation_observation = optional(15 + k);
  r.linearisation_inversion = optional(16 + k);
  r.linearisation_pose = optional(17 + k);
  const bool paired = !r.paired_reference.empty();
  if (paired != (r.paired_difference_m && r.paired_ci95_lower_m && r.paired_ci95_upper_m &&
                 r.paired_runs_lower)) {
    io::fail_at(path, number, "the paired_ columns are all set or all empty");
  }
  return r;
}

}  // namespace

void write_sweep_csv(const std::string& path, const SweepTable& table) {
  std::string text = header_of(table.keys) + "\n";
  for (const SweepRow& r : table.rows) {
    text += std::to_string(r.cell);
    for (const std::string& v : r.values) text += "," + field_text(v);
    text += "," + r.method + "," + std::to_string(r.runs) + "," + std::to_string(r.failed);
    for (const auto& v :
         {r.mean_error_m, r.p05_m, r.p50_m, r.p95_m, r.anees, r.nees_in_bounds_fraction}) {
      append_optional(text, v);
    }
    text += "," + r.paired_reference;
    for (const auto& v : {r.paired_difference_m, r.paired_ci95_lower_m, r.paired_ci95_upper_m}) {
      append_optional(text, v);
    }
    text += ",";
    if (r.paired_runs_lower) text += std::to_string(*r.paired_runs_lower);
    for (const auto& v :
         {r.linearisation_observation, r.linearisation_inversion, r.linearisation_pose}) {
      append_optional(text, v);
    }
    text += "\n";
  }
  io::write_text_atomically(path, text);
}

SweepTable read_sweep_csv(const std::string& path) {
  const std::string first = header_line(path);
  const std::vector<std::string> columns = header_columns(path, first);
  SweepTable table;
  table.keys.assign(columns.begin() + 1, columns.end() - kFigureCount);
  const std::size_t n = columns.size();
  io::for_each_csv_row(path, first, [&](std::string_view line, std::size_t number) {
    std::vector<std::string_view> f(n);
    io::split_csv_fields(line, path, number, f.data(), n);
    table.rows.push_back(parse_row(f, table.keys.size(), columns, path, number));
  });
  return table;
}

}  // namespace msislab::results
