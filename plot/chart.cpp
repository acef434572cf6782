#include "plot/chart.hpp"

#include <vtkAxis.h>
#include <vtkBrush.h>
#include <vtkChartLegend.h>
#include <vtkChartXY.h>
#include <vtkContextScene.h>
#include <vtkContextView.h>
#include <vtkDoubleArray.h>
#include <vtkNew.h>
#include <vtkPNGWriter.h>
#include <vtkPen.h>
#include <vtkPlot.h>
#include <vtkPlotPoints.h>
#include <vtkRenderWindow.h>
#include <vtkRenderer.h>
#include <vtkTable.h>
#include <vtkTextProperty.h>
#include <vtkUnsignedCharArray.h>
#include <vtkWindowToImageFilter.h>

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <array>
#include <cmath>
#include <filesystem>
#include <limits>

#include "io/atomic_file.hpp"
#include "io/input_error.hpp"

namespace msislab::plot {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

/// Text sizes and margins at the reference size of 1200 x 900 px; they scale with the height.
struct Layout {
  double scale = 1.0;
  int px(double reference) const { return static_cast<int>(std::lround(reference * scale)); }
  // The plot rectangle inside the window: room for the title, tick labels and axis titles.
  int left() const { return px(125); }
  int bottom() const { return px(105); }
  int right() const { return px(45); }
  int top() const { return px(80); }
};

/// VTK's embedded sans font draws '[' like '('; DejaVu Sans (fonts-dejavu-core) does not.
void set_font(vtkTextProperty* text, int size_pt, bool bold) {
  static const char* kRegular = "/usr/share/fonts/truetype/dejavu/DejaVuSans.ttf";
  static const char* kBold = "/usr/share/fonts/truetype/dejavu/DejaVuSans-Bold.ttf";
  const char* file = bold ? kBold : kRegular;
  if (std::filesystem::is_regular_file(file)) {
    text->SetFontFamily(VTK_FONT_FILE);
    text->SetFontFile(file);
  } else {
    text->SetFontFamilyToArial();
    text->SetBold(bold);
  }
  text->SetFontSize(size_pt);
  text->SetColor(0.0, 0.0, 0.0);
}

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

/// 1, 2, 2.5 or 5 times a power of ten, near span / target.
double nice_step(double span, int target) {
  const double raw = span / target;
  const double magnitude = std::pow(10.0, std::floor(std::log10(raw)));
  for (const double m : {1.0, 2.0, 2.5, 5.0}) {
    if (m * magnitude >= raw) return m * magnitude;
  }
  return 10.0 * magnitude;
}

void set_ticks(vtkAxis* axis, const AxisRange& range, double step) {
  vtkNew<vtkDoubleArray> positions;
  for (double k = std::ceil(range.min / step); k * step <= range.max; k += 1.0) {
    positions->InsertNextValue(k == 0.0 ? 0.0 : k * step);
  }
  axis->SetCustomTickPositions(positions);
}

/// The legend's size in pixels, estimated from its longest label (0 x 0 without entries).
struct LegendBox {
  int entries = 0;
  double w_px = 0.0;
  double h_px = 0.0;
};

LegendBox legend_box(const ChartSpec& spec, const Layout& layout) {
  LegendBox box;
  std::size_t longest = 0;
  for (const Series& s : spec.series) {
    if (s.label.empty()) continue;
    ++box.entries;
    longest = std::max(longest, s.label.size());
  }
  if (box.entries == 0) return box;
  box.w_px = static_cast<double>(longest) * 0.6 * layout.px(20) + layout.px(75);
  box.h_px = box.entries * 1.5 * layout.px(20) + layout.px(25);
  return box;
}

/// Equal aspect: one metres-per-pixel for both axes, the smallest that shows the data beside the
/// legend, which gets either a band at the top or one at the right (whichever costs less scale).
/// The data is centred, then moved down or left only as far as the legend needs.
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
    x0 += std::min(0.0, (x0 + m_per_px * (plot_w - legend.w_px)) - x.max);
  } else {
    y0 += std::min(0.0, (y0 + m_per_px * (plot_h - legend.h_px)) - y.max);
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

/// The first plot corner (0 top-right, 1 top-left, 2 bottom-right, 3 bottom-left) whose
/// legend-sized box covers no data point; -1 when there is none.
int emptiest_corner(const ChartSpec& spec, const AxisRange& x, const AxisRange& y, bool log_y,
                    double box_w, double box_h) {
  const auto to_unit_y = [&](double v) {
    return log_y ? (std::log10(v) - std::log10(y.min)) / (std::log10(y.max) - std::log10(y.min))
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
  return empty == counts.end() ? -1 : static_cast<int>(empty - counts.begin());
}

void add_series(vtkChartXY& chart, const Series& s) {
  vtkNew<vtkTable> table;
  vtkNew<vtkDoubleArray> xs, ys;
  xs->SetName("x");
  ys->SetName(s.label.empty() ? "y" : s.label.c_str());
  xs->SetNumberOfValues(static_cast<vtkIdType>(s.x.size()));
  ys->SetNumberOfValues(static_cast<vtkIdType>(s.y.size()));
  for (std::size_t i = 0; i < s.x.size(); ++i) {
    xs->SetValue(static_cast<vtkIdType>(i), s.x[i]);
    ys->SetValue(static_cast<vtkIdType>(i), s.y[i]);
  }
  table->AddColumn(xs);
  table->AddColumn(ys);
  vtkPlot* plot =
      chart.AddPlot(s.style == SeriesStyle::kPoints ? vtkChart::POINTS : vtkChart::LINE);
  plot->SetInputData(table, 0, 1);
  plot->SetColor(static_cast<unsigned char>(s.rgb >> 16 & 0xff),
                 static_cast<unsigned char>(s.rgb >> 8 & 0xff),
                 static_cast<unsigned char>(s.rgb & 0xff), 255);
  plot->SetLabel(s.label);
  plot->SetLegendVisibility(!s.label.empty());
  if (s.style == SeriesStyle::kPoints) {
    auto* points = vtkPlotPoints::SafeDownCast(plot);
    points->SetMarkerStyle(vtkPlotPoints::CIRCLE);
    points->SetMarkerSize(s.width_px);
    return;
  }
  plot->SetWidth(s.width_px);
  if (s.style == SeriesStyle::kDashedLine) plot->GetPen()->SetLineType(vtkPen::DASH_LINE);
  if (s.style == SeriesStyle::kDottedLine) plot->GetPen()->SetLineType(vtkPen::DOT_LINE);
}

void style_axis(vtkAxis* axis, const std::string& title, const Layout& layout) {
  axis->SetTitle(title);
  set_font(axis->GetTitleProperties(), layout.px(24), false);
  set_font(axis->GetLabelProperties(), layout.px(19), false);
  axis->GetPen()->SetWidth(1.5f);
  axis->GetGridPen()->SetColor(225, 225, 225, 255);
}

void set_range(vtkAxis* axis, const AxisRange& range, bool log) {
  axis->SetLogScale(log);
  axis->SetBehavior(vtkAxis::FIXED);
  axis->SetUnscaledRange(range.min, range.max);
}

/// Grows the range upwards so that the old one fills 1 - fraction of the axis.
void grow_top(AxisRange& y, bool log, double fraction) {
  if (log) {
    y.max = std::pow(10.0, std::log10(y.min) + std::log10(y.max / y.min) / (1.0 - fraction));
  } else {
    y.max = y.min + (y.max - y.min) / (1.0 - fraction);
  }
}

/// Puts the legend in the plot corner with the fewest data points under it; when every corner
/// has some, the y range grows so that the data leaves a band for it at the top.
void place_legend(vtkChartXY& chart, const ChartSpec& spec, const AxisRange& x, AxisRange& y,
                  bool log_y, const Layout& layout, const LegendBox& box, double plot_w,
                  double plot_h) {
  chart.SetShowLegend(box.entries > 0);
  if (box.entries == 0) return;
  vtkChartLegend* legend = chart.GetLegend();
  legend->SetLabelSize(layout.px(20));
  set_font(legend->GetLabelProperties(), layout.px(20), false);
  legend->SetSymbolWidth(layout.px(40));
  legend->GetBrush()->SetColor(255, 255, 255, 225);
  const double box_h = box.h_px / plot_h;
  int corner = emptiest_corner(spec, x, y, log_y, box.w_px / plot_w, box_h);
  if (corner < 0) {
    corner = 0;
    // Equal-aspect ranges already left a band for it; elsewhere the data moves down.
    if (!spec.equal_aspect) grow_top(y, log_y, box_h);
  }
  legend->SetHorizontalAlignment(corner % 2 == 0 ? vtkChartLegend::RIGHT : vtkChartLegend::LEFT);
  legend->SetVerticalAlignment(corner < 2 ? vtkChartLegend::TOP : vtkChartLegend::BOTTOM);
}

void write_png(const std::string& path, vtkRenderWindow* window) {
  window->Render();
  vtkNew<vtkWindowToImageFilter> capture;
  capture->SetInput(window);
  capture->SetInputBufferTypeToRGB();
  capture->ReadFrontBufferOff();
  capture->Update();
  vtkNew<vtkPNGWriter> writer;
  writer->SetWriteToMemory(true);
  writer->SetInputConnection(capture->GetOutputPort());
  writer->Write();
  vtkUnsignedCharArray* png = writer->GetResult();
  if (png == nullptr || png->GetNumberOfValues() == 0) io::fail_file(path, "PNG encoding failed");
  io::write_file_atomically(path, [&](std::ostream& out) {
    out.write(reinterpret_cast<const char*>(png->GetPointer(0)),
              static_cast<std::streamsize>(png->GetNumberOfValues()));
  });
}

}  // namespace

void append_ellipse(Series& series, const Eigen::Vector2d& mean, const Eigen::Matrix2d& cov,
                    double k_sigma, int segments) {
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix2d> eigen(cov);
  const Eigen::Vector2d sigmas = eigen.eigenvalues().cwiseMax(0.0).cwiseSqrt();
  if (!series.x.empty()) {
    series.x.push_back(kNaN);
    series.y.push_back(kNaN);
  }
  for (int i = 0; i <= segments; ++i) {
    const double angle = 2.0 * M_PI * i / segments;
    const Eigen::Vector2d p =
        mean + k_sigma * eigen.eigenvectors() *
                   Eigen::Vector2d(sigmas.x() * std::cos(angle), sigmas.y() * std::sin(angle));
    series.x.push_back(p.x());
    series.y.push_back(p.y());
  }
}

void write_chart_png(const std::string& path, const ChartSpec& spec) {
  const Bounds bounds = data_bounds(spec.series);
  if (bounds.empty()) io::fail_file(path, "nothing to draw: no finite data point");
  Layout layout;
  layout.scale = spec.height_px / 900.0;
  const double plot_w = spec.width_px - layout.left() - layout.right();
  const double plot_h = spec.height_px - layout.bottom() - layout.top();

  vtkNew<vtkContextView> view;
  vtkRenderWindow* window = view->GetRenderWindow();
  window->SetOffScreenRendering(1);
  window->SetSize(spec.width_px, spec.height_px);
  view->GetRenderer()->SetBackground(1.0, 1.0, 1.0);
  vtkNew<vtkChartXY> chart;
  view->GetScene()->AddItem(chart);
  chart->SetLayoutStrategy(vtkChart::AXES_TO_RECT);
  chart->SetSize(vtkRectf(static_cast<float>(layout.left()), static_cast<float>(layout.bottom()),
                          static_cast<float>(plot_w), static_cast<float>(plot_h)));
  chart->SetTitle(spec.title);
  set_font(chart->GetTitleProperties(), layout.px(28), true);
  for (const Series& s : spec.series) {
    if (!s.x.empty()) add_series(*chart, s);
  }

  vtkAxis* x_axis = chart->GetAxis(vtkAxis::BOTTOM);
  vtkAxis* y_axis = chart->GetAxis(vtkAxis::LEFT);
  style_axis(x_axis, spec.x_label, layout);
  style_axis(y_axis, spec.y_label, layout);
  const bool log_y = spec.log_y && all_positive_y(spec) && (!spec.y_range || spec.y_range->min > 0);
  AxisRange x = spec.x_range.value_or(padded(bounds.x_min, bounds.x_max, 0.0));
  AxisRange y = spec.y_range.value_or(log_y ? AxisRange{bounds.y_min / 1.2, bounds.y_max * 1.2}
                                            : padded(bounds.y_min, bounds.y_max, 0.05));
  const LegendBox legend = legend_box(spec, layout);
  if (spec.equal_aspect) {
    std::tie(x, y) = equal_aspect_ranges(bounds, plot_w, plot_h, legend);
    const double step = nice_step(std::max(x.max - x.min, y.max - y.min), 10);
    set_ticks(x_axis, x, step);
    set_ticks(y_axis, y, step);
  }
  place_legend(*chart, spec, x, y, log_y, layout, legend, plot_w, plot_h);
  set_range(x_axis, x, false);
  set_range(y_axis, y, log_y);
  write_png(path, window);
}

}  // namespace msislab::plot
