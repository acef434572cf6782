#include "io/sensitivity_csv.hpp"

#include "io/input_error.hpp"
#include "io/text_lines.hpp"

namespace msislab::io {

std::vector<SensitivityRow> read_sensitivity_csv(const std::string& path) {
  std::vector<SensitivityRow> rows;
  const std::size_t count =
      for_each_csv_row(path, kSensitivityHeader, [&](std::string_view line, std::size_t number) {
        const auto f = split_csv<8>(line, path, number);
        const auto error = [&](std::size_t i, std::string_view column) {
          const double metres = parse_finite(f[i], FieldAt{path, number, i + 1, column});
          if (metres < 0.0) fail_field(FieldAt{path, number, i + 1, column}, f[i], "is negative");
          return metres;
        };
        rows.push_back({std::string(f[0]), std::string(f[1]), std::string(f[2]),
                        error(3, "mean_error_m"), std::string(f[4]), error(5, "low_mean_error_m"),
                        std::string(f[6]), error(7, "high_mean_error_m")});
      });
  require_data_rows(path, count);
  return rows;
}

}  // namespace msislab::io
