// Chart layout, without a display: equal-aspect ranges give one metres-per-pixel on both axes and
// keep the data clear of the legend, the log axis falls back to linear for non-positive values,
// the legend moves the data down when no corner is free, and ellipses lie at k sigma.
#include "plot/chart_layout.hpp"

#include <gtest/gtest.h>

#include <Eigen/Cholesky>
#include <cmath>

#include "io/input_error.hpp"

namespace msislab::plot {
namespace {

Series line(std::vector<double> x, std::vector<double> y, const std::string& label = "a line") {
  return {label, std::move(x), std::move(y), SeriesStyle::kLine, 0xff0000, 2.0f};
}

double m_per_px_x(const ChartLayout& l) { return (l.x.max - l.x.min) / l.plot_w_px; }
double m_per_px_y(const ChartLayout& l) { return (l.y.max - l.y.min) / l.plot_h_px; }

/// Fractions of the plot (0..1 from the bottom left) where a point lands.
Eigen::Vector2d unit(const ChartLayout& l, double x, double y) {
  return {(x - l.x.min) / (l.x.max - l.x.min), (y - l.y.min) / (l.y.max - l.y.min)};
}

TEST(ChartLayout, EqualAspectWideAndTallData) {
  for (const auto& [x, y] : {std::pair<std::vector<double>, std::vector<double>>{{0, 100}, {0, 10}},
                             {{0, 10}, {-300, 0}}}) {
    ChartSpec spec;
    spec.equal_aspect = true;
    spec.series = {line(x, y)};
    const ChartLayout l = layout_chart(spec, "f.png");
    EXPECT_NEAR(m_per_px_x(l), m_per_px_y(l), 1e-12 * m_per_px_x(l));
    ASSERT_TRUE(l.tick_step);
    for (std::size_t i = 0; i < x.size(); ++i) {
      const Eigen::Vector2d u = unit(l, x[i], y[i]);
      EXPECT_TRUE(u.x() > 0 && u.x() < 1 && u.y() > 0 && u.y() < 1) << u.transpose();
    }
  }
}

TEST(ChartLayout, EqualAspectDataFillingThePlotLeavesTheLegendBand) {
  // Data with the plot's own aspect ratio: without a band the legend would cover a corner.
  ChartSpec spec;
  spec.equal_aspect = true;
  spec.series = {line({0, 103, 103, 0, 0}, {0, 0, 71.5, 71.5, 0}, "a long legend label here")};
  const ChartLayout l = layout_chart(spec, "f.png");
  EXPECT_NEAR(m_per_px_x(l), m_per_px_y(l), 1e-12 * m_per_px_x(l));
  EXPECT_EQ(l.legend_corner, LegendCorner::kTopRight);
  // The data's top right corner stays below or left of the legend (at least 60 px of band).
  const Eigen::Vector2d corner = unit(l, 103, 71.5);
  EXPECT_TRUE(corner.y() < 1.0 - 60.0 / l.plot_h_px || corner.x() < 1.0 - 60.0 / l.plot_w_px)
      << corner.transpose();
}

TEST(ChartLayout, LogAxisOnlyForPositiveValues) {
  ChartSpec spec;
  spec.log_y = true;
  spec.series = {line({0, 1, 2}, {0.5, 3, 40})};
  EXPECT_TRUE(layout_chart(spec, "f.png").log_y);
  spec.series.push_back(line({0, 1}, {0, 1}, ""));
  EXPECT_FALSE(layout_chart(spec, "f.png").log_y);
}

TEST(ChartLayout, NoFreeCornerMovesTheDataDown) {
  ChartSpec spec;
  spec.x_range = AxisRange{0, 1};
  spec.y_range = AxisRange{0, 1};
  spec.series = {line({0, 1}, {0, 1}), line({0, 1}, {1, 0})};  // a cross through every corner
  const ChartLayout l = layout_chart(spec, "f.png");
  EXPECT_EQ(l.legend_corner, LegendCorner::kTopRight);
  EXPECT_GT(l.y.max, 1.05);
  EXPECT_EQ(l.y.min, 0.0);

  spec.series = {line({0, 1}, {0, 1})};  // the top left is free
  EXPECT_EQ(layout_chart(spec, "f.png").legend_corner, LegendCorner::kTopLeft);
  EXPECT_EQ(layout_chart(spec, "f.png").y.max, 1.0);
}

TEST(ChartLayout, TextScalesWithTheHeight) {
  ChartSpec spec;
  spec.series = {line({0, 1}, {0, 1})};
  spec.width_px = 2400;
  spec.height_px = 1800;
  const ChartLayout l = layout_chart(spec, "f.png");
  EXPECT_EQ(l.text.title_pt, 2 * TextSizes{}.title_pt);
  EXPECT_EQ(l.left_px + l.plot_w_px + 90, 2400);
}

TEST(ChartLayout, NiceSteps) {
  EXPECT_DOUBLE_EQ(nice_step(160.0, 10), 20.0);
  EXPECT_DOUBLE_EQ(nice_step(28.0, 10), 5.0);
  EXPECT_DOUBLE_EQ(nice_step(22.0, 10), 2.5);
  EXPECT_DOUBLE_EQ(nice_step(1.0, 10), 0.1);
}

TEST(ChartLayout, NothingFiniteIsAnInputError) {
  ChartSpec spec;
  spec.series = {line({NAN}, {1.0})};
  EXPECT_THROW(layout_chart(spec, "f.png"), io::InputError);
}

TEST(Ellipse, PointsLieAtKSigmaAndEllipsesAreSeparated) {
  Series s;
  Eigen::Matrix2d cov;
  cov << 4.0, 1.5, 1.5, 1.0;
  append_ellipse(s, {10.0, -5.0}, cov, 2.0, 32);
  append_ellipse(s, {0.0, 0.0}, Eigen::Matrix2d::Identity(), 1.0, 32);
  ASSERT_EQ(s.x.size(), 2u * 33u + 1u);
  EXPECT_TRUE(std::isnan(s.x[33]) && std::isnan(s.y[33]));
  const Eigen::LLT<Eigen::Matrix2d> llt(cov);
  for (std::size_t i = 0; i < 33; ++i) {
    const Eigen::Vector2d d = Eigen::Vector2d(s.x[i], s.y[i]) - Eigen::Vector2d(10.0, -5.0);
    EXPECT_NEAR(std::sqrt(d.dot(llt.solve(d))), 2.0, 1e-9);
    EXPECT_NEAR(std::hypot(s.x[34 + i], s.y[34 + i]), 1.0, 1e-12);
  }
}

}  // namespace
}  // namespace msislab::plot
