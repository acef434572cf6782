// Charts rendered by VTK: the PNG has the requested size and a white background, a circle drawn
// with equal aspect comes out round in pixels, and nothing is written when there is nothing to
// draw. Needs an X display: CMake runs it under `xvfb-run -a`; without any display it skips.
#include "plot/chart.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <opencv2/core.hpp>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include "io/input_error.hpp"
#include "plot/display.hpp"
#include "test_support.hpp"

namespace msislab::plot {
namespace {

#define REQUIRE_X_DISPLAY()                                                                      \
  do {                                                                                           \
    if (!x_display_available())                                                                  \
      GTEST_SKIP() << "no X display: VTK cannot draw (run under `xvfb-run -a`, or install xvfb " \
                      "and xauth so that CMake does)";                                           \
  } while (0)

TEST(Chart, EqualAspectCircleIsRound) {
  REQUIRE_X_DISPLAY();
  const testing::TempDir tmp;
  ChartSpec spec;
  spec.title = "A circle of 10 m";
  spec.x_label = "x [m]";
  spec.y_label = "y [m]";
  spec.equal_aspect = true;
  spec.width_px = 1000;
  spec.height_px = 600;
  Series circle{"", {}, {}, SeriesStyle::kLine, 0xff0000, 3.0f};  // not in the legend
  append_ellipse(circle, {0.0, 0.0}, Eigen::Matrix2d::Identity() * 25.0, 2.0);
  // Far points make the data much wider than tall.
  const Series ends{"ends", {-60.0, 60.0}, {0.0, 0.0}, SeriesStyle::kPoints, 0x0000ff, 6.0f};
  spec.series = {ends, circle};
  const std::string path = tmp.file("circle.png");
  ChartWriter().write_png(path, spec);

  const cv::Mat image = cv::imread(path, cv::IMREAD_COLOR);
  ASSERT_EQ(image.cols, 1000);
  ASSERT_EQ(image.rows, 600);
  EXPECT_EQ(image.at<cv::Vec3b>(5, 5), cv::Vec3b(255, 255, 255));
  // The circle's pixels: pure red.
  cv::Mat red;
  cv::inRange(image, cv::Scalar(0, 0, 200), cv::Scalar(60, 60, 255), red);
  std::vector<cv::Point> pixels;
  cv::findNonZero(red, pixels);
  ASSERT_GT(pixels.size(), 100u);
  const cv::Rect box = cv::boundingRect(pixels);
  EXPECT_GT(box.width, 40);
  EXPECT_NEAR(box.width, box.height, 3) << "the circle is " << box.width << " x " << box.height;
  EXPECT_EQ(std::filesystem::directory_iterator(tmp.path())->path().filename(), "circle.png");
}

/// The bounding box of the pixels near a colour given as 0xRRGGBB.
cv::Rect pixels_of(const cv::Mat& image, std::uint32_t rgb) {
  const cv::Scalar bgr(rgb & 0xff, rgb >> 8 & 0xff, rgb >> 16 & 0xff);
  cv::Mat mask;
  cv::inRange(image, bgr - cv::Scalar(40, 40, 40), bgr + cv::Scalar(40, 40, 40), mask);
  std::vector<cv::Point> pixels;
  cv::findNonZero(mask, pixels);
  return pixels.empty() ? cv::Rect() : cv::boundingRect(pixels);
}

TEST(Chart, PanelsSitSideBySideTopAligned) {
  REQUIRE_X_DISPLAY();
  const testing::TempDir tmp;
  ChartSpec left;
  left.title = "left";
  left.width_px = 600;
  left.height_px = 450;
  left.series = {{"red", {0.0, 1.0}, {0.0, 1.0}, SeriesStyle::kLine, 0xff0000, 3.0f}};
  ChartSpec right = left;
  right.title = "right";
  right.width_px = 500;
  right.height_px = 300;
  right.series = {{"blue", {0.0, 1.0}, {1.0, 0.0}, SeriesStyle::kLine, 0x0000ff, 3.0f}};
  const std::string path = tmp.file("panels.png");
  ChartWriter().write_png(path, std::vector<ChartSpec>{left, right});

  const cv::Mat image = cv::imread(path, cv::IMREAD_COLOR);
  ASSERT_EQ(image.cols, 1100);
  ASSERT_EQ(image.rows, 450);
  const cv::Rect red = pixels_of(image, 0xff0000), blue = pixels_of(image, 0x0000ff);
  ASSERT_GT(red.area(), 0);
  ASSERT_GT(blue.area(), 0);
  EXPECT_LT(red.br().x, 600);
  EXPECT_GE(blue.x, 600);
  EXPECT_LT(blue.br().y, 300) << "the shorter panel sits at the top";
  EXPECT_GT(red.br().y, 300);
}

TEST(Chart, NothingToDrawIsAnInputErrorAndWritesNothing) {
  REQUIRE_X_DISPLAY();
  const testing::TempDir tmp;
  ChartSpec spec;
  spec.series = {{"empty", {}, {}, SeriesStyle::kLine, 0, 1.0f}};
  EXPECT_THROW(ChartWriter().write_png(tmp.file("x.png"), spec), io::InputError);
  EXPECT_THROW(ChartWriter().write_png(tmp.file("x.png"), std::vector<ChartSpec>{}),
               io::InputError);
  EXPECT_TRUE(std::filesystem::is_empty(tmp.path()));
}

}  // namespace
}  // namespace msislab::plot
