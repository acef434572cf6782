#include "report/sweep_figures.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdlib>
#include <map>
#include <optional>
#include <set>
#include <stdexcept>

#include "report/method_styles.hpp"
#include "report/plot_figures.hpp"

namespace msislab::report {

namespace {

/// The sweep figures' y values: per metric, its kinds (one line per method and kind) and the value
/// with its band of a row.
struct SweepMetric {
  std::string y_label, title;
  std::vector<std::string> kinds;  ///< "" for a metric of one kind
  bool log_y = false;
  std::optional<double> value(const results::SweepRow& r, std::size_t kind) const;
  std::optional<std::pair<double, double>> band(const results::SweepRow& r) const;
  std::string name;
  std::string reference;  ///< paired_difference: the method the differences are taken against
};

SweepMetric sweep_metric(const std::string& metric, const results::SweepTable& table) {
  SweepMetric m;
  m.name = metric;
  m.kinds = {""};
  if (metric == "mean_error") {
    m.y_label = "mean position error [m]";
    m.title = "Mean error (dotted: 5-95 % of runs)";
  } else if (metric == "anees") {
    m.y_label = "ANEES";
    m.title = "ANEES";
    m.log_y = true;
  } else if (metric == "paired_difference") {
    for (const results::SweepRow& r : table.rows) {
      if (!r.paired_reference.empty()) m.reference = r.paired_reference;
    }  // the y label names it, in the chart's styles (sweep_chart)
    m.title = "Paired difference (dotted: 95 % interval)";
  } else if (metric == "linearisation") {
    m.y_label = "linearisation error epsilon";
    m.title = "Linearisation error";
    m.kinds = {"match update", "inversion", "pose read-out"};
    m.log_y = true;
  } else {
    throw std::invalid_argument("sweep_chart: unknown metric '" + metric + "'");
  }
  return m;
}

std::optional<double> SweepMetric::value(const results::SweepRow& r, std::size_t kind) const {
  if (name == "mean_error") return r.mean_error_m;
  if (name == "anees") return r.anees;
  if (name == "paired_difference") return r.paired_difference_m;
  const std::optional<double> v = std::array{r.linearisation_observation, r.linearisation_inversion,
                                             r.linearisation_pose}[kind];
  return v && *v > 0.0 ? v : std::nullopt;  // a log axis
}

std::optional<std::pair<double, double>> SweepMetric::band(const results::SweepRow& r) const {
  if (name == "mean_error" && r.p05_m && r.p95_m) return std::pair{*r.p05_m, *r.p95_m};
  if (name == "paired_difference" && r.paired_ci95_lower_m && r.paired_ci95_upper_m) {
    return std::pair{*r.paired_ci95_lower_m, *r.paired_ci95_upper_m};
  }
  return std::nullopt;
}

}  // namespace

bool sweep_has_metric(const results::SweepTable& table, const std::string& metric) {
  const SweepMetric m = sweep_metric(metric, table);
  for (const results::SweepRow& r : table.rows) {
    for (std::size_t kind = 0; kind < m.kinds.size(); ++kind) {
      if (m.value(r, kind)) return true;
    }
  }
  return false;
}

namespace {

/// The swept key's values in first-seen order and their x: the number, else the rank (then
/// `ranks` names them: "0: a, 1: b").
struct SweepAxis {
  std::vector<std::string> values;
  std::vector<double> x_of;
  std::string ranks;

  double x(const std::string& value) const {
    const auto at = std::find(values.begin(), values.end(), value) - values.begin();
    return x_of[static_cast<std::size_t>(at)];
  }
};

SweepAxis sweep_axis(const results::SweepTable& table, std::size_t key) {
  SweepAxis axis;
  bool numeric = true;
  for (const results::SweepRow& r : table.rows) {
    if (std::find(axis.values.begin(), axis.values.end(), r.values[key]) == axis.values.end()) {
      axis.values.push_back(r.values[key]);
    }
  }
  axis.x_of.resize(axis.values.size());
  for (std::size_t i = 0; i < axis.values.size(); ++i) {
    char* end = nullptr;
    axis.x_of[i] = std::strtod(axis.values[i].c_str(), &end);
    numeric = numeric && end != axis.values[i].c_str() && *end == '\0';
  }
  if (!numeric) {
    for (std::size_t i = 0; i < axis.values.size(); ++i) {
      axis.x_of[i] = static_cast<double>(i);
      axis.ranks += (axis.ranks.empty() ? "" : ", ") + std::to_string(i) + ": " + axis.values[i];
    }
  }
  return axis;
}

/// The name of the line a row belongs to: one line per method (and kind) and combination of the
/// other keys' values, by their last name ("Robocentric SLAM, iekf_iterations=1"). When each value
/// of the swept key is one cell (a list whose other keys move with it), one line per method (and
/// kind); another key whose value follows the swept key's (a filter sigma set with the noise it
/// models) does not split the lines.
class SweepLineNames {
 public:
  SweepLineNames(const MethodStyles& styles, const results::SweepTable& table, std::size_t key,
                 const SweepMetric& metric, std::size_t value_count)
      : styles_(styles),
        table_(table),
        key_(key),
        metric_(metric),
        follows_(table.keys.size(), false) {
    std::set<int> cells;
    for (const results::SweepRow& r : table.rows) cells.insert(r.cell);
    one_cell_per_value_ = cells.size() == value_count;
    for (std::size_t k = 0; k < table.keys.size(); ++k) {
      std::map<std::string, std::string> value_at;
      bool determined = true;
      for (const results::SweepRow& r : table.rows) {
        const auto [it, inserted] = value_at.emplace(r.values[key], r.values[k]);
        determined = determined && (inserted || it->second == r.values[k]);
      }
      follows_[k] = determined;
    }
  }

  std::string operator()(const results::SweepRow& r, std::size_t kind) const {
    std::string name = styles_.title(r.method);
    if (!metric_.kinds[kind].empty()) name += ": " + metric_.kinds[kind];
    for (std::size_t k = 0; k < table_.keys.size() && !one_cell_per_value_; ++k) {
      if (k != key_ && !follows_[k])
        name += ", " + table_.keys[k].substr(table_.keys[k].rfind('.') + 1) + "=" + r.values[k];
    }
    return name;
  }

 private:
  const MethodStyles& styles_;
  const results::SweepTable& table_;
  std::size_t key_;
  const SweepMetric& metric_;
  std::vector<bool> follows_;
  bool one_cell_per_value_ = false;
};

/// Adds one line (its band dotted when the metric has one); `shade` counts each method's lines so
/// far, each a darker shade. A line needs two points (VTK refuses shorter ones); a single value is
/// drawn as its point, labelled.
void add_sweep_line(const MethodStyles& styles, plot::ChartSpec& chart,
                    const results::SweepTable& table, std::size_t key, const SweepMetric& m,
                    const SweepAxis& axis, const SweepLineNames& line_of,
                    const std::pair<std::string, std::size_t>& line,
                    std::map<std::string, int>& shade) {
  const auto& [name, kind] = line;
  std::string method;
  std::vector<std::pair<double, const results::SweepRow*>> points;
  for (const results::SweepRow& r : table.rows) {
    if (line_of(r, kind) != name) continue;
    method = r.method;
    points.emplace_back(axis.x(r.values[key]), &r);
  }
  std::sort(points.begin(), points.end(),
            [](const auto& a, const auto& b) { return a.first < b.first; });
  plot::Series mid{name, {}, {}, styles.line(method), 0, 2.5f};
  plot::Series low{"", {}, {}, plot::SeriesStyle::kDottedLine, 0, 1.5f};
  plot::Series high{"", {}, {}, plot::SeriesStyle::kDottedLine, 0, 1.5f};
  for (const auto& [x, r] : points) {
    const std::optional<double> y = m.value(*r, kind);
    if (!y) continue;
    mid.x.push_back(x);
    mid.y.push_back(*y);
    if (const auto band = m.band(*r)) {
      low.x.push_back(x);
      low.y.push_back(band->first);
      high.x.push_back(x);
      high.y.push_back(band->second);
    }
  }
  if (mid.x.empty()) return;
  const std::uint32_t rgb = darker(styles.colour(method), std::pow(0.6, shade[method]++));
  mid.rgb = low.rgb = high.rgb = rgb;
  if (low.x.size() > 1) {
    chart.series.push_back(std::move(low));
    chart.series.push_back(std::move(high));
  }
  plot::Series points_of_mid = mid;
  points_of_mid.style = plot::SeriesStyle::kPoints;
  points_of_mid.width_px = 8.0f;
  if (mid.x.size() > 1) {
    points_of_mid.label.clear();
    chart.series.push_back(std::move(mid));
  }
  chart.series.push_back(std::move(points_of_mid));
}

}  // namespace

plot::ChartSpec sweep_chart(const MethodStyles& styles, const results::SweepTable& table,
                            std::size_t key, const std::string& metric, int width_px,
                            int height_px) {
  SweepMetric m = sweep_metric(metric, table);
  if (m.name == "paired_difference") {
    m.y_label = "mean error minus " + styles.title(m.reference) + "'s, same runs [m]";
  }
  plot::ChartSpec chart = empty_chart(table.keys[key], m.y_label, width_px, height_px);
  chart.log_y = m.log_y;
  const SweepAxis axis = sweep_axis(table, key);
  chart.title = m.title + " vs " + table.keys[key].substr(table.keys[key].rfind('.') + 1) +
                (axis.ranks.empty() ? "" : " (" + axis.ranks + ")");
  const SweepLineNames line_of(styles, table, key, m, axis.values.size());
  std::vector<std::pair<std::string, std::size_t>> lines;  // name, kind
  for (std::size_t kind = 0; kind < m.kinds.size(); ++kind) {
    for (const results::SweepRow& r : table.rows) {
      const std::pair line{line_of(r, kind), kind};
      if (std::find(lines.begin(), lines.end(), line) == lines.end()) lines.push_back(line);
    }
  }
  std::map<std::string, int> shade;
  for (const auto& line : lines)
    add_sweep_line(styles, chart, table, key, m, axis, line_of, line, shade);
  const double x_min = *std::min_element(axis.x_of.begin(), axis.x_of.end());
  const double x_max = *std::max_element(axis.x_of.begin(), axis.x_of.end());
  if (metric == "anees" || metric == "paired_difference") {
    const double level = metric == "anees" ? 3.0 : 0.0;
    chart.series.push_back({metric == "anees" ? "consistent (3)" : "no difference",
                            {x_min, x_max},
                            {level, level},
                            plot::SeriesStyle::kDottedLine,
                            0x888888,
                            2.0f});
  }
  return chart;
}

}  // namespace msislab::report
