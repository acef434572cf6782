// One x-y chart described as plain data and rendered to PNG with VTK's charts (vtkChartXY in a
// vtkContextActor of an offscreen render window, read back through vtkWindowToImageFilter, encoded
// by vtkPNGWriter and written atomically). Rendering needs an X display: see plot/display.hpp.
#pragma once

#include <Eigen/Core>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

namespace msislab::plot {

enum class SeriesStyle { kLine, kDashedLine, kDottedLine, kPoints };

/// One curve or point set. A NaN in x or y breaks a line, so one series can hold many ellipses.
struct Series {
  std::string label;  ///< legend text; empty: not in the legend
  std::vector<double> x;
  std::vector<double> y;
  SeriesStyle style = SeriesStyle::kLine;
  std::uint32_t rgb = 0x000000;  ///< colour as 0xRRGGBB
  float width_px = 2.0f;         ///< line width, or marker size for points
};

struct AxisRange {
  double min = 0.0;
  double max = 1.0;
};

struct ChartSpec {
  std::string title;
  std::string x_label;  ///< with the unit, e.g. "x [m]"
  std::string y_label;
  std::vector<Series> series;  ///< drawn in order: the last on top
  /// x-y maps: the axis ranges are chosen so that one metre on x spans as many pixels as on y.
  bool equal_aspect = false;
  bool log_y = false;                ///< used only when every finite y is > 0
  std::optional<AxisRange> x_range;  ///< fixed range; automatic when absent
  std::optional<AxisRange> y_range;
  int width_px = 1200;
  int height_px = 900;
};

/// Draws charts into PNG files. Every chart gets its own offscreen render window, and all of them
/// share the one X connection this object opens (VTK would open one per window and abort when
/// that fails).
class ChartWriter {
 public:
  /// Opens the X display; io::InputError when there is none (plot/display.hpp).
  ChartWriter();
  ~ChartWriter();
  ChartWriter(const ChartWriter&) = delete;
  ChartWriter& operator=(const ChartWriter&) = delete;

  /// Renders the chart and writes it to path as PNG, atomically. Throws io::InputError when there
  /// is nothing to draw or the file cannot be written.
  void write_png(const std::string& path, const ChartSpec& chart) const;
  /// Several charts side by side in one PNG, left to right and top-aligned, each at its own
  /// width_px x height_px: the figure is as wide as their sum and as tall as the tallest.
  void write_png(const std::string& path, const std::vector<ChartSpec>& panels) const;

 private:
  void* display_ = nullptr;  ///< Xlib Display*
};

/// Appends the closed k-sigma ellipse of a 2x2 covariance around mean to series (NaN-separated
/// from what is already there).
void append_ellipse(Series& series, const Eigen::Vector2d& mean, const Eigen::Matrix2d& cov,
                    double k_sigma, int segments = 64);

}  // namespace msislab::plot
