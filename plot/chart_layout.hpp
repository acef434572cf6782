// Where a chart's parts go, decided before VTK draws it (pure arithmetic, no display): text sizes
// and the plot rectangle for the figure size, axis ranges (equal aspect for maps, a log axis when
// possible), the tick step of maps, and the corner that leaves the legend clear of the data.
#pragma once

#include <optional>

#include "plot/chart.hpp"

namespace msislab::plot {

/// Pixel sizes at the reference figure of 1200 x 900 px, scaled with the figure's height.
struct TextSizes {
  int title_pt = 28;
  int axis_title_pt = 24;
  int tick_label_pt = 19;
  int legend_pt = 20;
  int legend_symbol_px = 40;
};

enum class LegendCorner { kTopRight, kTopLeft, kBottomRight, kBottomLeft };

struct ChartLayout {
  double scale = 1.0;  ///< figure height / 900 px: text, margins and line widths follow it
  TextSizes text;
  // The plot rectangle (the axes' box) inside the figure, in pixels from the bottom left.
  int left_px = 0;
  int bottom_px = 0;
  int plot_w_px = 0;
  int plot_h_px = 0;
  AxisRange x;
  AxisRange y;
  bool log_y = false;
  std::optional<double> tick_step;  ///< equal aspect: the same step on both axes
  bool show_legend = false;
  LegendCorner legend_corner = LegendCorner::kTopRight;
};

/// Throws io::InputError naming path when the chart has no finite data point.
ChartLayout layout_chart(const ChartSpec& spec, const std::string& path);

/// 1, 2, 2.5 or 5 times a power of ten, near span / target.
double nice_step(double span, int target);

}  // namespace msislab::plot
