#include "report/plot_figures.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdlib>
#include <map>
#include <optional>
#include <set>
#include <stdexcept>

#include "io/text_lines.hpp"
#include "report/method_styles.hpp"

namespace msislab::report {

namespace {

constexpr std::uint32_t kTruthColour = 0x202020;
constexpr std::uint32_t kMapPointColour = 0xa8a8a8;
constexpr std::uint32_t kBoundColour = 0x555555;
constexpr double kEllipseSigmas = 2.0;
constexpr std::size_t kEllipsesPerFigure = 25;

std::string ordinal(std::size_t k) {
  const std::size_t last = k % 10, last_two = k % 100;
  const char* suffix = (last_two >= 11 && last_two <= 13) ? "th"
                       : last == 1                        ? "st"
                       : last == 2                        ? "nd"
                       : last == 3                        ? "rd"
                                                          : "th";
  return std::to_string(k) + suffix;
}

std::string truth_label(const dataset::Truth& truth) {
  return truth.kind == "gps" ? "GPS" : truth.kind + " truth";
}

/// The figure title's mean error: error_stats' mean, 0 without samples.
double title_error_m(const std::vector<ErrorSample>& errors) {
  const std::optional<ErrorStats> stats = error_stats(errors);
  return stats ? stats->mean_m : 0.0;
}

plot::Series ellipses(const MethodStyles& styles, const ResultData& result, int every) {
  const std::size_t n = result.scans.size();
  const std::size_t k =
      every > 0 ? static_cast<std::size_t>(every)
                : std::max<std::size_t>(1, (n + kEllipsesPerFigure - 1) / kEllipsesPerFigure);
  plot::Series series;
  series.label =
      "2-sigma position, " + (k == 1 ? std::string("every scan") : "every " + ordinal(k) + " scan");
  series.rgb = darker(styles.colour(result.method), 0.6);
  series.width_px = 1.5f;
  for (std::size_t i = 0; i < n; i += k) {
    const GaussianPose2& s = result.scans[i].pose;
    plot::append_ellipse(series, s.mean.translation(), s.cov.topLeftCorner<2, 2>(), kEllipseSigmas);
  }
  return series;
}

/// Rows of one method, in file order.
std::vector<std::pair<std::string, std::vector<results::NeesRow>>> by_method(
    const std::vector<results::NeesRow>& rows) {
  std::vector<std::pair<std::string, std::vector<results::NeesRow>>> groups;
  for (const results::NeesRow& row : rows) {
    auto it = std::find_if(groups.begin(), groups.end(),
                           [&](const auto& g) { return g.first == row.method; });
    if (it == groups.end()) it = groups.insert(groups.end(), {row.method, {}});
    it->second.push_back(row);
  }
  return groups;
}

/// The bounds per scan when every method has the same ones (the same number of runs), else none.
std::optional<std::vector<results::NeesRow>> shared_bounds(
    const std::vector<std::pair<std::string, std::vector<results::NeesRow>>>& groups) {
  std::map<long long, results::NeesRow> bounds;
  for (const auto& [method, rows] : groups) {
    for (const results::NeesRow& r : rows) {
      const auto [it, inserted] = bounds.try_emplace(r.scan, r);
      if (!inserted && (it->second.lower != r.lower || it->second.upper != r.upper)) {
        return std::nullopt;
      }
    }
  }
  std::vector<results::NeesRow> rows;
  for (const auto& [scan, row] : bounds) rows.push_back(row);
  return rows;
}

/// The share of scans whose run-averaged NEES lies inside its bounds, as "82%".
std::string in_bounds_percent(const std::vector<results::NeesRow>& rows) {
  const auto inside = std::count_if(rows.begin(), rows.end(), [](const results::NeesRow& r) {
    return r.lower <= r.mean_nees && r.mean_nees <= r.upper;
  });
  return io::format_fixed(100.0 * static_cast<double>(inside) / static_cast<double>(rows.size()),
                          0) +
         "%";
}

void add_bounds(plot::ChartSpec& chart, const std::vector<results::NeesRow>& rows,
                const std::string& label, std::uint32_t rgb) {
  plot::Series lower{label, {}, {}, plot::SeriesStyle::kDashedLine, rgb, 2.0f};
  plot::Series upper{"", {}, {}, plot::SeriesStyle::kDashedLine, rgb, 2.0f};
  for (const results::NeesRow& r : rows) {
    lower.x.push_back(static_cast<double>(r.scan));
    lower.y.push_back(r.lower);
    upper.x.push_back(static_cast<double>(r.scan));
    upper.y.push_back(r.upper);
  }
  chart.series.push_back(std::move(lower));
  chart.series.push_back(std::move(upper));
}

}  // namespace

std::uint32_t darker(std::uint32_t rgb, double factor) {
  std::uint32_t out = 0;
  for (const int shift : {16, 8, 0}) {
    const auto channel = static_cast<double>(rgb >> shift & 0xff);
    out |= static_cast<std::uint32_t>(std::lround(channel * factor)) << shift;
  }
  return out;
}

plot::ChartSpec empty_chart(const std::string& x_label, const std::string& y_label, int width_px,
                            int height_px) {
  plot::ChartSpec chart;
  chart.x_label = x_label;
  chart.y_label = y_label;
  chart.width_px = width_px;
  chart.height_px = height_px;
  return chart;
}

plot::ChartSpec trajectory_chart(const MethodStyles& styles, const ResultData& result,
                                 int ellipse_every, int width_px, int height_px) {
  plot::ChartSpec chart = empty_chart("x (East) [m]", "y (North) [m]", width_px, height_px);
  chart.equal_aspect = true;
  chart.title = styles.title(result.method);
  if (result.truth) chart.title += " vs " + truth_label(*result.truth);
  if (!result.errors.empty()) {
    chart.title += ": mean error " + io::format_fixed(title_error_m(result.errors), 2) + " m";
  }
  if (!result.map_points_m.empty()) {
    plot::Series points{"map points (" + std::to_string(result.map_points_m.size()) + ")",
                        {},
                        {},
                        plot::SeriesStyle::kPoints,
                        kMapPointColour,
                        2.5f};
    for (const Eigen::Vector2d& p : result.map_points_m) {
      points.x.push_back(p.x());
      points.y.push_back(p.y());
    }
    chart.series.push_back(std::move(points));
  }
  if (result.truth) {
    plot::Series truth{truth_label(*result.truth), {},           {},
                       plot::SeriesStyle::kLine,   kTruthColour, 2.5f};
    for (const PositionFix& f : result.truth->positions) {
      truth.x.push_back(f.p_world_m.x());
      truth.y.push_back(f.p_world_m.y());
    }
    chart.series.push_back(std::move(truth));
  }
  plot::Series estimate{styles.title(result.method),  {},  {}, plot::SeriesStyle::kLine,
                        styles.colour(result.method), 2.5f};
  for (const StampedPose& p : result.trajectory) {
    estimate.x.push_back(p.pose.mean.x());
    estimate.y.push_back(p.pose.mean.y());
  }
  chart.series.push_back(std::move(estimate));
  if (!result.scans.empty()) chart.series.push_back(ellipses(styles, result, ellipse_every));
  return chart;
}

plot::ChartSpec error_chart(const MethodStyles& styles,
                            const std::vector<const ResultData*>& results, int width_px,
                            int height_px) {
  plot::ChartSpec chart = empty_chart("time [s]", "position error [m]", width_px, height_px);
  double t_max_s = 0.0, error_max_m = 0.0;
  for (const ResultData* r : results) {
    if (r->errors.empty()) continue;
    const double t0_s = r->truth->positions.front().t_s;
    plot::Series line{
        styles.title(r->method) + " (mean " + io::format_fixed(title_error_m(r->errors), 2) + " m)",
        {},
        {},
        styles.line(r->method),
        styles.colour(r->method),
        2.5f};
    for (const ErrorSample& e : r->errors) {
      line.x.push_back(e.t_s - t0_s);
      line.y.push_back(e.error_m);
      t_max_s = std::max(t_max_s, e.t_s - t0_s);
      error_max_m = std::max(error_max_m, e.error_m);
    }
    chart.series.push_back(std::move(line));
    if (chart.title.empty()) chart.title = "Position error against " + truth_label(*r->truth);
  }
  if (chart.series.size() == 1) {
    chart.title = "Position error of " + styles.title(results.front()->method) + " against " +
                  truth_label(*results.front()->truth);
  }
  chart.x_range = plot::AxisRange{0.0, std::max(t_max_s, 1.0)};
  chart.y_range = plot::AxisRange{0.0, std::max(1.1 * error_max_m, 0.1)};
  return chart;
}

plot::ChartSpec nees_chart(const MethodStyles& styles, const std::vector<results::NeesRow>& rows,
                           int width_px, int height_px) {
  plot::ChartSpec chart = empty_chart("scan index", "NEES", width_px, height_px);
  chart.log_y = true;
  const auto groups = by_method(rows);
  const std::optional<std::vector<results::NeesRow>> shared = shared_bounds(groups);
  long long runs_min = rows.front().runs, runs_max = rows.front().runs;
  double scan_min = static_cast<double>(rows.front().scan), scan_max = scan_min;
  for (const results::NeesRow& r : rows) {
    runs_min = std::min(runs_min, r.runs);
    runs_max = std::max(runs_max, r.runs);
    scan_min = std::min(scan_min, static_cast<double>(r.scan));
    scan_max = std::max(scan_max, static_cast<double>(r.scan));
  }
  const std::string runs =
      runs_min == runs_max ? std::to_string(runs_min) + " runs"
                           : std::to_string(runs_min) + "-" + std::to_string(runs_max) + " runs";
  chart.title = "Scan pose NEES averaged over " + runs;
  chart.series.push_back({"expected value (3 DOF)",
                          {scan_min, scan_max},
                          {3.0, 3.0},
                          plot::SeriesStyle::kDottedLine,
                          0x888888,
                          2.0f});
  if (shared) add_bounds(chart, *shared, "95% bounds", kBoundColour);
  for (const auto& [method, method_rows] : groups) {
    if (!shared) {
      add_bounds(chart, method_rows, styles.title(method) + " 95% bounds", styles.colour(method));
    }
    plot::Series mean{styles.title(method) + " (" + in_bounds_percent(method_rows) + " in bounds)",
                      {},
                      {},
                      styles.line(method),
                      styles.colour(method),
                      2.5f};
    for (const results::NeesRow& r : method_rows) {
      mean.x.push_back(static_cast<double>(r.scan));
      mean.y.push_back(r.mean_nees);
    }
    chart.series.push_back(std::move(mean));
  }
  chart.x_range = plot::AxisRange{scan_min, std::max(scan_max, scan_min + 1.0)};
  return chart;
}

plot::ChartSpec error_spread_chart(const MethodStyles& styles,
                                   const std::vector<results::ErrorSpreadRow>& rows, int width_px,
                                   int height_px) {
  plot::ChartSpec chart = empty_chart("time [s]", "position error [m]", width_px, height_px);
  int runs = 0;
  std::vector<std::string> order;
  for (const results::ErrorSpreadRow& r : rows) {
    runs = std::max(runs, r.spread.runs);
    if (std::find(order.begin(), order.end(), r.method) == order.end()) order.push_back(r.method);
  }
  chart.title = "Position error over " + std::to_string(runs) + " runs (dotted: 5-95 %)";
  for (const std::string& method : order) {
    // The mean in the method's own style (world-centric dashed over the robocentric line it
    // coincides with), the band dotted.
    plot::Series mean{styles.title(method) + " mean", {},  {}, styles.line(method),
                      styles.colour(method),          2.5f};
    plot::Series low{styles.title(method) + " 5-95 %",
                     {},
                     {},
                     plot::SeriesStyle::kDottedLine,
                     styles.colour(method),
                     1.5f};
    plot::Series high{"", {}, {}, plot::SeriesStyle::kDottedLine, styles.colour(method), 1.5f};
    for (const results::ErrorSpreadRow& r : rows) {
      if (r.method != method) continue;
      for (plot::Series* s : {&mean, &low, &high}) s->x.push_back(r.spread.t_s);
      mean.y.push_back(r.spread.mean_m);
      low.y.push_back(r.spread.p05_m);
      high.y.push_back(r.spread.p95_m);
    }
    chart.series.push_back(std::move(low));
    chart.series.push_back(std::move(high));
    chart.series.push_back(std::move(mean));
  }
  return chart;
}

plot::ChartSpec error_distribution_chart(const MethodStyles& styles,
                                         const std::vector<ErrorHistogram>& histograms,
                                         int width_px, int height_px) {
  plot::ChartSpec chart =
      empty_chart("position error [m]", "fraction of samples per bin", width_px, height_px);
  chart.title = "Position error distribution (all runs, once a second)";
  for (const ErrorHistogram& h : histograms) {
    // The histogram's outline: up and down each bin's edges.
    plot::Series outline{styles.title(h.method),  {},  {}, styles.line(h.method),
                         styles.colour(h.method), 2.5f};
    outline.x.push_back(h.edges_m.front());
    outline.y.push_back(0.0);
    for (std::size_t b = 0; b < h.fractions.size(); ++b) {
      outline.x.insert(outline.x.end(), {h.edges_m[b], h.edges_m[b + 1]});
      outline.y.insert(outline.y.end(), {h.fractions[b], h.fractions[b]});
    }
    outline.x.push_back(h.edges_m.back());
    outline.y.push_back(0.0);
    chart.series.push_back(std::move(outline));
  }
  return chart;
}

}  // namespace msislab::report
