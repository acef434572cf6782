// The fidelity table (docs/fidelity.md): one row per statistic with the real and the simulated
// value, their ratio and, for distributions, the Kolmogorov-Smirnov distance; rendered as Markdown
// and as the JSON rows of fidelity.json. Any statistic of two datasets is one more row.
#pragma once

#include <limits>
#include <optional>
#include <string>
#include <vector>

#include "dataset/detected_beams.hpp"
#include "io/json.hpp"

namespace msislab::report {

struct FidelityRow {
  std::string section;  ///< the group it is printed under, e.g. "Per beam"
  std::string key;      ///< stable machine name, e.g. "first_range_median_m"
  std::string name;     ///< what a reader sees, e.g. "first detected range, median"
  double real = std::numeric_limits<double>::quiet_NaN();
  double sim = std::numeric_limits<double>::quiet_NaN();
  std::optional<double> ks;  ///< KS distance of the distribution behind the row
  std::string unit;          ///< "%", "m", "s", "m/s", "deg"; empty for a plain number
  int decimals = 2;          ///< decimals of the printed values
};

using FidelityTable = std::vector<FidelityRow>;

/// sim / real; NaN when either is not finite or real is 0.
double ratio(const FidelityRow& row);

/// The sonar rows: per beam, detected ranges by band, readings per scan, rotation.
/// max_range_m sets the 10 m bands (0-10, 10-20, ... up to the sonar range).
FidelityTable sonar_rows(const SonarStatistics& real, const SonarStatistics& sim,
                         double max_range_m);

/// A Markdown table: statistic (with its unit), real, simulated, sim / real, KS; a bold line
/// opens each section. Undefined values print as "-".
std::string fidelity_markdown(const FidelityTable& table);

/// The rows as a JSON array of objects {section, key, name, unit, real, sim, ratio, ks}; an
/// undefined value is NaN (written as null) or null.
io::Json fidelity_rows_json(const FidelityTable& table);

}  // namespace msislab::report
