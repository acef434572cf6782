#include "plot/chart_layout.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>

#include "io/input_error.hpp"

namespace msislab::plot {
namespace {

struct Bounds {
  double x_min = std::numeric_limits<double>::infinity(), x_max = -x_min;
  double y_min = x_min, y_max = -x_min;
  bool empty() const { return !(x_min <= x_max); }
};

Bounds data_bounds(const std::vector<Series>& series) {
  Bounds b;
  for (const Series& s : series) {
    for (std::size_t i = 0; i < s.x.size(); ++i) {
      if (!std::isfinite(s.x[i]) || !std::isfinite(s.y[i])) continue;
      b.x_min = std::min(b.x_min, s.x[i]);
      b.x_max = std::max(b.x_max, s.x[i]);
      b.y_min = std::min(b.y_min, s.y[i]);
      b.y_max = std::max(b.y_max, s.y[i]);
    }
  }
  return b;
}

AxisRange padded(double min, double max, double fraction) {
  const double span = max > min ? max - min : std::max(std::abs(max), 1.0);
  return {min - fraction * span, max + fraction * span};
}

int scaled(int reference, double scale) { return static_cast<int>(std::lround(reference * scale)); }

/// The legend's size in pixels, estimated from its longest label (0 x 0 without entries).
struct LegendBox {
  int entries = 0;
  double w_px = 0.0;
  double h_px = 0.0;
};

LegendBox legend_box(const ChartSpec& spec, const TextSizes& text) {
  LegendBox box;
  std::size_t longest = 0;
  for (const Series& s : spec.series) {
    if (s.label.empty()) continue;
    ++box.entries;
    longest = std::max(longest, s.label.size());
  }
  if (box.entries == 0) return box;
  box.w_px = static_cast<double>(longest) * 0.6 * text.legend_pt + 1.9 * text.legend_symbol_px;
  box.h_px = (1.5 * box.entries + 2.0) * text.legend_pt;
  return box;
}

/// Equal aspect: one metres-per-pixel for both axes, the smallest that shows the data beside the
/// legend, which gets either a band at the top or one at the right (whichever costs less scale).
/// The data is centred, then moved down or left only as far as the legend needs (the range's
/// start grows until the data's end is clear of the band).
std::pair<AxisRange, AxisRange> equal_aspect_ranges(const Bounds& b, double plot_w, double plot_h,
                                                    const LegendBox& legend) {
  const AxisRange x = padded(b.x_min, b.x_max, 0.04), y = padded(b.y_min, b.y_max, 0.04);
  const double dx = x.max - x.min, dy = y.max - y.min;
  const double top_band = std::max(dx / plot_w, dy / (plot_h - legend.h_px));
  const double right_band = std::max(dx / (plot_w - legend.w_px), dy / plot_h);
  const double m_per_px = std::min(top_band, right_band);
  double x0 = 0.5 * (x.min + x.max) - 0.5 * m_per_px * plot_w;
  double y0 = 0.5 * (y.min + y.max) - 0.5 * m_per_px * plot_h;
  if (right_band < top_band) {
    x0 += std::max(0.0, x.max - (x0 + m_per_px * (plot_w - legend.w_px)));
  } else {
    y0 += std::max(0.0, y.max - (y0 + m_per_px * (plot_h - legend.h_px)));
  }
  return {{x0, x0 + m_per_px * plot_w}, {y0, y0 + m_per_px * plot_h}};
}

bool all_positive_y(const ChartSpec& spec) {
  for (const Series& s : spec.series) {
    for (const double y : s.y) {
      if (std::isfinite(y) && y <= 0.0) return false;
    }
  }
  return true;
}

/// The first corner (in LegendCorner order) whose legend-sized box, as fractions of the plot,
/// covers no data point.
std::optional<LegendCorner> empty_corner(const ChartSpec& spec, const ChartLayout& layout,
                                         double box_w, double box_h) {
  const AxisRange& x = layout.x;
  const AxisRange& y = layout.y;
  const auto to_unit_y = [&](double v) {
    return layout.log_y ? std::log10(v / y.min) / std::log10(y.max / y.min)
                        : (v - y.min) / (y.max - y.min);
  };
  std::array<std::size_t, 4> counts{};
  for (const Series& s : spec.series) {
    for (std::size_t i = 0; i < s.x.size(); ++i) {
      if (!std::isfinite(s.x[i]) || !std::isfinite(s.y[i])) continue;
      const double u = (s.x[i] - x.min) / (x.max - x.min), v = to_unit_y(s.y[i]);
      const bool right = u > 1.0 - box_w, left = u < box_w;
      const bool top = v > 1.0 - box_h, bottom = v < box_h;
      counts[0] += right && top;
      counts[1] += left && top;
      counts[2] += right && bottom;
      counts[3] += left && bottom;
    }
  }
  const auto empty = std::find(counts.begin(), counts.end(), 0u);
  if (empty == counts.end()) return std::nullopt;
  return static_cast<LegendCorner>(empty - counts.begin());
}

/// Grows the range upwards so that the old one fills 1 - fraction of the axis.
void grow_top(AxisRange& y, bool log, double fraction) {
  if (log) {
    y.max = y.min * std::pow(y.max / y.min, 1.0 / (1.0 - fraction));
  } else {
    y.max = y.min + (y.max - y.min) / (1.0 - fraction);
  }
}

}  // namespace

double nice_step(double span, int target) {
  const double raw = span / target;
  const double magnitude = std::pow(10.0, std::floor(std::log10(raw)));
  for (const double m : {1.0, 2.0, 2.5, 5.0}) {
    if (m * magnitude >= raw) return m * magnitude;
  }
  return 10.0 * magnitude;
}

ChartLayout layout_chart(const ChartSpec& spec, const std::string& path) {
  const Bounds bounds = data_bounds(spec.series);
  if (bounds.empty()) io::fail_file(path, "nothing to draw: no finite data point");
  ChartLayout layout;
  const double scale = spec.height_px / 900.0;
  layout.scale = scale;
  const TextSizes reference;
  layout.text = {scaled(reference.title_pt, scale), scaled(reference.axis_title_pt, scale),
                 scaled(reference.tick_label_pt, scale), scaled(reference.legend_pt, scale),
                 scaled(reference.legend_symbol_px, scale)};
  // Room for the title above, tick labels and axis titles left and below.
  layout.left_px = scaled(125, scale);
  layout.bottom_px = scaled(105, scale);
  layout.plot_w_px = spec.width_px - layout.left_px - scaled(45, scale);
  layout.plot_h_px = spec.height_px - layout.bottom_px - scaled(80, scale);

  layout.log_y = spec.log_y && all_positive_y(spec) && (!spec.y_range || spec.y_range->min > 0);
  layout.x = spec.x_range.value_or(padded(bounds.x_min, bounds.x_max, 0.0));
  layout.y = spec.y_range.value_or(layout.log_y ? AxisRange{bounds.y_min / 1.2, bounds.y_max * 1.2}
                                                : padded(bounds.y_min, bounds.y_max, 0.05));
  const LegendBox legend = legend_box(spec, layout.text);
  if (spec.equal_aspect) {
    std::tie(layout.x, layout.y) =
        equal_aspect_ranges(bounds, layout.plot_w_px, layout.plot_h_px, legend);
    layout.tick_step =
        nice_step(std::max(layout.x.max - layout.x.min, layout.y.max - layout.y.min), 10);
  }
  layout.show_legend = legend.entries > 0;
  const double box_h = legend.h_px / layout.plot_h_px;
  const std::optional<LegendCorner> corner =
      empty_corner(spec, layout, legend.w_px / layout.plot_w_px, box_h);
  layout.legend_corner = corner.value_or(LegendCorner::kTopRight);
  // No corner is free: the data moves down to leave a band at the top (equal-aspect ranges
  // have left one already).
  if (!corner && !spec.equal_aspect) grow_top(layout.y, layout.log_y, box_h);
  return layout;
}

}  // namespace msislab::plot
