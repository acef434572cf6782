#include "report/fidelity_figures.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "io/text_lines.hpp"
#include "stats/sample_statistics.hpp"

namespace msislab::report {

namespace {

constexpr double kHistogramBin_m = 1.0;
constexpr double kRingStep_m = 10.0;
constexpr int kRangePanelWidth_px = 1100;
// 900 px high like every msislab figure: VTK's text at other sizes leaves stray marks under the
// tick labels (under Xvfb).
constexpr int kRangePanelHeight_px = 900;
constexpr int kRevolutionPanel_px = 900;

struct Colours {
  std::uint32_t line;  ///< histogram lines and first ranges
  std::uint32_t bins;  ///< detected bins, lighter
};
constexpr Colours kReal{0x202020, 0xb4b4b4};
constexpr Colours kSim{0x1f77b4, 0xaec7e8};

/// A histogram of 1 m bins over [0, max_range_m] as a staircase, in percent of the sample per m.
plot::Series histogram(const std::vector<double>& values_m, double max_range_m,
                       const std::string& label, plot::SeriesStyle style, std::uint32_t rgb) {
  const auto bins = static_cast<std::size_t>(std::ceil(max_range_m / kHistogramBin_m - 1e-9));
  std::vector<double> counts(std::max<std::size_t>(bins, 1), 0.0);
  for (const double v : values_m) {
    if (v < 0.0 || v > max_range_m) continue;
    counts[std::min(static_cast<std::size_t>(v / kHistogramBin_m), counts.size() - 1)] += 1.0;
  }
  const double scale =
      values_m.empty() ? 0.0 : 100.0 / (static_cast<double>(values_m.size()) * kHistogramBin_m);
  plot::Series series{label, {}, {}, style, rgb, 2.5f};
  for (std::size_t k = 0; k < counts.size(); ++k) {
    const double left_m = static_cast<double>(k) * kHistogramBin_m;
    for (const double x : {left_m, left_m + kHistogramBin_m}) {
      series.x.push_back(x);
      series.y.push_back(counts[k] * scale);
    }
  }
  return series;
}

std::string legend(const FigureSide& side) { return side.role + " (" + side.dataset + ")"; }

plot::ChartSpec range_panel(const std::string& title, const std::string& y_label,
                            double max_range_m) {
  plot::ChartSpec chart;
  chart.title = title;
  chart.x_label = "range [m]";
  chart.y_label = y_label;
  chart.x_range = plot::AxisRange{0.0, max_range_m};
  chart.width_px = kRangePanelWidth_px;
  chart.height_px = kRangePanelHeight_px;
  return chart;
}

/// Circles of 10, 20, ... m around the sonar head, in one NaN-separated series.
plot::Series range_rings(const SonarMount& mount, double max_range_m) {
  plot::Series rings{"", {}, {}, plot::SeriesStyle::kLine, 0xd0d0d0, 1.5f};
  for (double r = kRingStep_m; r <= max_range_m + 1e-9; r += kRingStep_m) {
    plot::append_ellipse(rings, {mount.x_m, mount.y_m}, Eigen::Matrix2d::Identity() * r * r, 1.0,
                         180);
  }
  return rings;
}

plot::ChartSpec revolution_panel(const FigureSide& side, const Colours& colours,
                                 double max_range_m) {
  plot::Series bins{"detected bins", {}, {}, plot::SeriesStyle::kPoints, colours.bins, 2.5f};
  plot::Series first{"first range of a beam",    {},           {},
                     plot::SeriesStyle::kPoints, colours.line, 5.0f};
  std::size_t beams = 0;
  for (const DetectedBeam& beam : *side.beams) {
    if (beam.keyframe != side.keyframe) continue;
    ++beams;
    const double bearing_rad = sonar_bearing_in_vehicle(beam.angle_rad, side.mount);
    const Eigen::Vector2d head(side.mount.x_m, side.mount.y_m);
    const Eigen::Vector2d axis(std::cos(bearing_rad), std::sin(bearing_rad));
    for (const double r : beam.ranges_m) {
      const Eigen::Vector2d p = head + r * axis;
      bins.x.push_back(p.x());
      bins.y.push_back(p.y());
    }
    const Eigen::Vector2d p =
        head + *std::min_element(beam.ranges_m.begin(), beam.ranges_m.end()) * axis;
    first.x.push_back(p.x());
    first.y.push_back(p.y());
  }
  plot::ChartSpec chart;
  chart.title = side.role + ": keyframe " + std::to_string(side.keyframe) + ", " +
                std::to_string(beams) + " beams, " + io::format_count(bins.x.size()) + " bins";
  chart.x_label = "x (forward) [m]";
  chart.y_label = "y (port) [m]";
  chart.equal_aspect = true;
  chart.width_px = kRevolutionPanel_px;
  chart.height_px = kRevolutionPanel_px;
  chart.series = {range_rings(side.mount, max_range_m), std::move(bins), std::move(first),
                  plot::Series{"vehicle, heading +x",
                               {3.0, -1.5, -1.5, 3.0},
                               {0.0, 1.2, -1.2, 0.0},
                               plot::SeriesStyle::kLine,
                               0xd62728,
                               2.5f}};
  return chart;
}

}  // namespace

std::vector<plot::ChartSpec> range_charts(const FigureSide& real, const FigureSide& sim,
                                          double max_range_m) {
  // One panel: a sample of each side as histograms overlaid, its KS distance in the title.
  const auto panel = [&](const std::string& title, const std::string& y_label,
                         const std::vector<double>& real_m, const std::vector<double>& sim_m,
                         const std::string& unit) {
    plot::ChartSpec chart =
        range_panel(title + " (KS " + io::format_fixed(ks_distance(real_m, sim_m), 3) + ")",
                    y_label, max_range_m);
    chart.series = {
        histogram(real_m, max_range_m, legend(real) + ": " + io::format_count(real_m.size()) + unit,
                  plot::SeriesStyle::kLine, kReal.line),
        histogram(sim_m, max_range_m, legend(sim) + ": " + io::format_count(sim_m.size()) + unit,
                  plot::SeriesStyle::kDashedLine, kSim.line)};
    double y_max = 0.0;
    for (const plot::Series& series : chart.series) {
      for (const double y : series.y) y_max = std::max(y_max, y);
    }
    chart.y_range = plot::AxisRange{0.0, std::max(1.1 * y_max, 1.0)};
    return chart;
  };
  const SonarStatistics& r = *real.stats;
  const SonarStatistics& s = *sim.stats;
  return {panel("First detected range of a beam", "beams [% per m]", r.first_ranges_m,
                s.first_ranges_m, " beams"),
          panel("All detected bins", "detected bins [% per m]", r.detected_ranges_m,
                s.detected_ranges_m, " bins")};
}

std::vector<plot::ChartSpec> revolution_charts(const FigureSide& real, const FigureSide& sim,
                                               double max_range_m) {
  return {revolution_panel(real, kReal, max_range_m), revolution_panel(sim, kSim, max_range_m)};
}

}  // namespace msislab::report
