#include "plot/chart.hpp"

#include <vtkAxis.h>
#include <vtkBrush.h>
#include <vtkChartLegend.h>
#include <vtkChartXY.h>
#include <vtkContextActor.h>
#include <vtkContextScene.h>
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
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <limits>

#include "io/atomic_file.hpp"
#include "io/input_error.hpp"
#include "plot/chart_layout.hpp"
#include "plot/display.hpp"

namespace msislab::plot {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

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

void set_ticks(vtkAxis* axis, const AxisRange& range, double step) {
  vtkNew<vtkDoubleArray> positions;
  for (double k = std::ceil(range.min / step); k * step <= range.max; k += 1.0) {
    positions->InsertNextValue(k == 0.0 ? 0.0 : k * step);
  }
  axis->SetCustomTickPositions(positions);
}

/// One series as a VTK plot; widths scale with the figure (1 at 900 px high).
void add_series(vtkChartXY& chart, const Series& s, float scale) {
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
    points->SetMarkerSize(s.width_px * scale);
    return;
  }
  plot->SetWidth(s.width_px * scale);
  if (s.style == SeriesStyle::kDashedLine) plot->GetPen()->SetLineType(vtkPen::DASH_LINE);
  if (s.style == SeriesStyle::kDottedLine) plot->GetPen()->SetLineType(vtkPen::DOT_LINE);
}

void style_axis(vtkAxis* axis, const std::string& title, const ChartLayout& layout) {
  axis->SetTitle(title);
  set_font(axis->GetTitleProperties(), layout.text.axis_title_pt, false);
  set_font(axis->GetLabelProperties(), layout.text.tick_label_pt, false);
  axis->GetPen()->SetWidth(1.5f * static_cast<float>(layout.scale));
  axis->GetGridPen()->SetColor(225, 225, 225, 255);
}

void set_range(vtkAxis* axis, const AxisRange& range, bool log, std::optional<double> step) {
  if (step) set_ticks(axis, range, *step);
  axis->SetLogScale(log);
  axis->SetBehavior(vtkAxis::FIXED);
  axis->SetUnscaledRange(range.min, range.max);
}

void style_legend(vtkChartXY& chart, const ChartLayout& layout) {
  chart.SetShowLegend(layout.show_legend);
  vtkChartLegend* legend = chart.GetLegend();
  legend->SetLabelSize(layout.text.legend_pt);
  set_font(legend->GetLabelProperties(), layout.text.legend_pt, false);
  legend->SetSymbolWidth(layout.text.legend_symbol_px);
  legend->GetBrush()->SetColor(255, 255, 255, 225);
  const bool right = layout.legend_corner == LegendCorner::kTopRight ||
                     layout.legend_corner == LegendCorner::kBottomRight;
  const bool top = layout.legend_corner == LegendCorner::kTopRight ||
                   layout.legend_corner == LegendCorner::kTopLeft;
  legend->SetHorizontalAlignment(right ? vtkChartLegend::RIGHT : vtkChartLegend::LEFT);
  legend->SetVerticalAlignment(top ? vtkChartLegend::TOP : vtkChartLegend::BOTTOM);
}

void capture_png(const std::string& path, vtkRenderWindow* window) {
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

/// One chart into the scene, its figure's bottom-left corner at (left_px, bottom_px).
void add_chart(vtkContextScene& scene, const ChartSpec& spec, const ChartLayout& layout,
               int left_px, int bottom_px) {
  vtkNew<vtkChartXY> chart;
  scene.AddItem(chart);
  chart->SetLayoutStrategy(vtkChart::AXES_TO_RECT);
  chart->SetSize(vtkRectf(static_cast<float>(left_px + layout.left_px),
                          static_cast<float>(bottom_px + layout.bottom_px),
                          static_cast<float>(layout.plot_w_px),
                          static_cast<float>(layout.plot_h_px)));
  chart->SetTitle(spec.title);
  set_font(chart->GetTitleProperties(), layout.text.title_pt, true);
  for (const Series& s : spec.series) {
    if (!s.x.empty()) add_series(*chart, s, static_cast<float>(layout.scale));
  }
  vtkAxis* x_axis = chart->GetAxis(vtkAxis::BOTTOM);
  vtkAxis* y_axis = chart->GetAxis(vtkAxis::LEFT);
  style_axis(x_axis, spec.x_label, layout);
  style_axis(y_axis, spec.y_label, layout);
  set_range(x_axis, layout.x, false, layout.tick_step);
  set_range(y_axis, layout.y, layout.log_y, layout.tick_step);
  style_legend(*chart, layout);
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

ChartWriter::ChartWriter() : display_(open_x_display()) {
  if (display_ == nullptr) {
    const char* name = std::getenv("DISPLAY");
    throw io::InputError(std::string("cannot open the X display '") + (name ? name : "") +
                         "' to draw with VTK (run under `xvfb-run -a`)");
  }
}

ChartWriter::~ChartWriter() { close_x_display(display_); }

void ChartWriter::write_png(const std::string& path, const ChartSpec& spec) const {
  write_png(path, std::vector<ChartSpec>{spec});
}

void ChartWriter::write_png(const std::string& path, const std::vector<ChartSpec>& panels) const {
  if (panels.empty()) io::fail_file(path, "nothing to draw: no chart");
  std::vector<ChartLayout> layouts;
  int width_px = 0, height_px = 0;
  for (const ChartSpec& spec : panels) {
    layouts.push_back(layout_chart(spec, path));
    width_px += spec.width_px;
    height_px = std::max(height_px, spec.height_px);
  }
  // A window, a renderer and a context actor holding the charts: no vtkContextView, whose X
  // interactor (never needed offscreen) can crash in XSync while it is initialised.
  vtkNew<vtkRenderWindow> window;
  window->SetDisplayId(display_);
  window->SetOffScreenRendering(1);
  window->SetSize(width_px, height_px);
  vtkNew<vtkRenderer> renderer;
  renderer->SetBackground(1.0, 1.0, 1.0);
  window->AddRenderer(renderer);
  vtkNew<vtkContextActor> actor;
  actor->GetScene()->SetRenderer(renderer);
  renderer->AddActor(actor);
  int left_px = 0;
  for (std::size_t i = 0; i < panels.size(); ++i) {
    // Panels are top-aligned: a shorter one starts lower.
    add_chart(*actor->GetScene(), panels[i], layouts[i], left_px, height_px - panels[i].height_px);
    left_px += panels[i].width_px;
  }
  capture_png(path, window);
}

}  // namespace msislab::plot
