#include "settings/footprint_yaml.hpp"

#include <cmath>
#include <limits>
#include <sstream>

#include "settings/config_fields.hpp"

namespace msislab::settings {

namespace {

constexpr double kDeg = M_PI / 180.0;

void require_ascending(io::YamlMap& map, const std::string& key, const std::vector<double>& v) {
  if (v.empty()) map.fail(key, "needs at least one node");
  for (std::size_t i = 1; i < v.size(); ++i) {
    if (!(v[i] > v[i - 1])) map.fail(key, "nodes must be ascending");
  }
}

std::string list(const std::vector<double>& v, int precision) {
  std::ostringstream out;
  out.setf(std::ios::fixed);
  out.precision(precision);
  out << '[';
  for (std::size_t i = 0; i < v.size(); ++i) out << (i ? ", " : "") << v[i];
  out << ']';
  return out.str();
}

/// The table's keys, all or none.
void read_table(io::YamlMap& map, FootprintTable& t) {
  if (!map.numbers("ranges_m", t.ranges_m)) map.fail_required("ranges_m", "is required");
  require_ascending(map, "ranges_m", t.ranges_m);
  if (t.ranges_m.front() < 0.0) map.fail("ranges_m", "ranges must be >= 0");
  std::vector<double> incidences_deg;
  if (!map.numbers("incidences_deg", incidences_deg)) {
    map.fail_required("incidences_deg", "is required");
  }
  require_ascending(map, "incidences_deg", incidences_deg);
  if (incidences_deg.front() < 0.0 || incidences_deg.back() > 90.0) {
    map.fail("incidences_deg", "incidences lie in [0, 90] deg");
  }
  for (const double a : incidences_deg) t.incidences_rad.push_back(a * kDeg);
  long long min_samples = 0;
  if (!map.integer("min_samples", min_samples)) map.fail_required("min_samples", "is required");
  if (min_samples < 2) map.fail("min_samples", "must be at least 2");
  if (!map.has("rows")) map.fail_required("rows", "is required");
  const YAML::Node rows = map.node("rows");
  if (!rows.IsSequence() || rows.size() != t.ranges_m.size()) {
    map.fail_node(rows, "rows",
                  "expected one row per range (" + std::to_string(t.ranges_m.size()) + ")");
  }
  constexpr double kNan = std::numeric_limits<double>::quiet_NaN();
  const std::size_t n = incidences_deg.size();
  const std::string size = "expected one entry per incidence (" + std::to_string(n) + ")";
  for (std::size_t i = 0; i < rows.size(); ++i) {
    io::YamlMap row(rows[i], map.file(), map.path_of("rows") + "[" + std::to_string(i) + "]",
                    rows[i].Mark().line);
    std::vector<double> offset_m, sd_m, samples;
    if (!row.numbers("offset_m", offset_m) || offset_m.size() != n) row.fail("offset_m", size);
    if (!row.numbers("sd_m", sd_m) || sd_m.size() != n) row.fail("sd_m", size);
    if (!row.numbers("samples", samples) || samples.size() != n) row.fail("samples", size);
    for (std::size_t j = 0; j < n; ++j) {
      if (sd_m[j] < 0.0) row.fail("sd_m", "a spread must be >= 0");
      if (samples[j] < 0.0 || samples[j] != std::floor(samples[j])) {
        row.fail("samples", "counts are whole numbers >= 0");
      }
      const bool figure = samples[j] >= static_cast<double>(min_samples);
      t.offset_m.push_back(figure ? offset_m[j] : kNan);
      t.sd_m.push_back(figure ? sd_m[j] : kNan);
    }
    row.finish();
  }
}

}  // namespace

void read_footprint_section(io::YamlMap map, FootprintConfig& c) {
  if (map.has("ranges_m") || map.has("incidences_deg") || map.has("min_samples") ||
      map.has("rows")) {
    c.table = FootprintTable{};
    read_table(map, c.table);
  }
  read_line_normals(map, c.line);
  map.finish();
}

bool has_footprint_section(const std::string& config_path) {
  const YAML::Node root = io::load_yaml_file(config_path);
  return root.IsMap() && root["footprint"];
}

std::string footprint_section_yaml(const FootprintEstimate& estimate, int min_samples,
                                   const LineNormalConfig& line, const std::string& comment) {
  std::ostringstream out;
  std::istringstream lines(comment);
  for (std::string text; std::getline(lines, text);) out << "# " << text << '\n';
  const FootprintTable& t = estimate.table;
  std::vector<double> incidences_deg;
  for (const double a : t.incidences_rad) incidences_deg.push_back(a / kDeg);
  out << "footprint:\n"
      << "  ranges_m: " << list(t.ranges_m, 3) << '\n'
      << "  incidences_deg: " << list(incidences_deg, 3) << '\n'
      << "  min_samples: " << min_samples << '\n'
      << "  # One row per range: per incidence, the mean and the spread (m) of the range\n"
      << "  # reported less the range on the beam's axis, and the samples behind them.\n"
      << "  rows:\n";
  const std::size_t n = t.incidences_rad.size();
  for (std::size_t i = 0; i < t.ranges_m.size(); ++i) {
    std::vector<double> offset_m, sd_m, samples;
    for (std::size_t j = 0; j < n; ++j) {
      const std::size_t c = i * n + j;
      const bool figure = estimate.samples[c] >= min_samples && std::isfinite(t.offset_m[c]);
      offset_m.push_back(figure ? t.offset_m[c] : 0.0);
      sd_m.push_back(figure ? t.sd_m[c] : 0.0);
      samples.push_back(estimate.samples[c]);
    }
    out << "    - {offset_m: " << list(offset_m, 4) << ", sd_m: " << list(sd_m, 4)
        << ", samples: " << list(samples, 0) << "}\n";
  }
  out << "  line_radius_m: " << line.radius_m << '\n'
      << "  line_min_points: " << line.min_points << '\n'
      << "  line_max_eigen_ratio: " << line.max_eigen_ratio << '\n';
  return out.str();
}

}  // namespace msislab::settings
