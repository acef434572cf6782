#include "plot/scan_figures.hpp"

#include <Eigen/Geometry>
#include <opencv2/core.hpp>
#include <opencv2/imgproc.hpp>

#include "io/input_error.hpp"
#include "io/png_file.hpp"

namespace msislab::plot {

namespace {

cv::Scalar colour(int bgr) { return cv::Scalar(bgr >> 16 & 0xff, bgr >> 8 & 0xff, bgr & 0xff); }

/// World metres -> pixels: uniform scale, y up, a margin around the bounds.
struct View {
  Eigen::AlignedBox2d box;
  double px_per_m = 1.0;
  int margin_px = 40;
  int top_px = 40;  ///< room for the title
  cv::Point to_px(const Eigen::Vector2d& p) const {
    return {margin_px + static_cast<int>((p.x() - box.min().x()) * px_per_m),
            top_px + static_cast<int>((box.max().y() - p.y()) * px_per_m)};
  }
  cv::Size size() const {
    return {2 * margin_px + static_cast<int>(box.sizes().x() * px_per_m) + 1,
            top_px + margin_px + static_cast<int>(box.sizes().y() * px_per_m) + 1};
  }
};

View view_of(const Eigen::AlignedBox2d& box, int width_px) {
  View view;
  view.box = box;
  view.px_per_m = (width_px - 2.0 * view.margin_px) / std::max(box.sizes().x(), 1.0);
  return view;
}

void draw_scale_bar(cv::Mat& image, const View& view, double length_m) {
  const cv::Point a(view.margin_px, image.rows - 15);
  const cv::Point b = a + cv::Point(static_cast<int>(length_m * view.px_per_m), 0);
  cv::line(image, a, b, cv::Scalar(0, 0, 0), 2);
  cv::putText(image, std::to_string(static_cast<int>(length_m)) + " m", a + cv::Point(0, -6),
              cv::FONT_HERSHEY_SIMPLEX, 0.45, cv::Scalar(0, 0, 0), 1, cv::LINE_AA);
}

void draw_points(cv::Mat& image, const View& view, const std::vector<Eigen::Vector2d>& points,
                 const cv::Scalar& c) {
  for (const Eigen::Vector2d& p : points) {
    const cv::Point px = view.to_px(p);
    if (px.inside(cv::Rect(0, 0, image.cols, image.rows)))
      image.at<cv::Vec3b>(px) = {static_cast<std::uint8_t>(c[0]), static_cast<std::uint8_t>(c[1]),
                                 static_cast<std::uint8_t>(c[2])};
  }
}

}  // namespace

void write_map_png(const std::string& path, const std::string& title,
                   const std::vector<Eigen::Vector2d>& points_m, const std::vector<Track>& tracks,
                   int width_px) {
  Eigen::AlignedBox2d box;
  for (const Track& t : tracks) {
    for (const auto& p : t.points_m) box.extend(p);
  }
  for (const auto& p : points_m) box.extend(p);
  if (box.isEmpty()) io::fail_file(path, "nothing to draw");
  const View view = view_of(box, width_px);
  cv::Mat image(view.size(), CV_8UC3, cv::Scalar(255, 255, 255));
  draw_points(image, view, points_m, cv::Scalar(90, 90, 90));
  int legend_y = view.top_px + 10;
  for (const Track& t : tracks) {
    std::vector<cv::Point> polyline;
    for (const auto& p : t.points_m) polyline.push_back(view.to_px(p));
    cv::polylines(image, polyline, false, colour(t.bgr), 2, cv::LINE_AA);
    cv::line(image, {image.cols - 190, legend_y}, {image.cols - 160, legend_y}, colour(t.bgr), 3);
    cv::putText(image, t.label, {image.cols - 152, legend_y + 5}, cv::FONT_HERSHEY_SIMPLEX, 0.45,
                cv::Scalar(0, 0, 0), 1, cv::LINE_AA);
    legend_y += 20;
  }
  cv::putText(image, title, {view.margin_px, 25}, cv::FONT_HERSHEY_SIMPLEX, 0.6,
              cv::Scalar(0, 0, 0), 1, cv::LINE_AA);
  draw_scale_bar(image, view, box.sizes().maxCoeff() > 120.0 ? 50.0 : 10.0);
  io::write_png(path, image);
}

void write_scan_comparison_png(const std::string& path, const std::string& title,
                               const std::vector<Eigen::Vector2d>& before_m,
                               const std::vector<Eigen::Vector2d>& after_m) {
  // Scan frame: x forward drawn up, y port drawn left: plot (-y, x).
  auto rotate = [](const std::vector<Eigen::Vector2d>& in) {
    std::vector<Eigen::Vector2d> out;
    for (const auto& p : in) out.emplace_back(-p.y(), p.x());
    return out;
  };
  const auto a = rotate(before_m), b = rotate(after_m);
  Eigen::AlignedBox2d box(Eigen::Vector2d(-1, -1), Eigen::Vector2d(1, 1));
  for (const auto& p : a) box.extend(p);
  for (const auto& p : b) box.extend(p);
  const View view = view_of(box, 520);
  const cv::Size panel = view.size();
  cv::Mat image(panel.height, 2 * panel.width, CV_8UC3, cv::Scalar(255, 255, 255));
  const char* labels[] = {"before: every reading at the central pose", "after: motion compensated"};
  for (int k = 0; k < 2; ++k) {
    cv::Mat half = image(cv::Rect(k * panel.width, 0, panel.width, panel.height));
    for (const auto& p : k == 0 ? a : b) {
      cv::circle(half, view.to_px(p), 1, cv::Scalar(160, 60, 20), cv::FILLED, cv::LINE_AA);
    }
    cv::drawMarker(half, view.to_px({0, 0}), cv::Scalar(0, 0, 220), cv::MARKER_TRIANGLE_UP, 12, 2);
    cv::putText(half, labels[k], {view.margin_px, 25}, cv::FONT_HERSHEY_SIMPLEX, 0.5,
                cv::Scalar(0, 0, 0), 1, cv::LINE_AA);
    draw_scale_bar(half, view, 10.0);
  }
  cv::putText(image, title, {view.margin_px, panel.height - 35}, cv::FONT_HERSHEY_SIMPLEX, 0.45,
              cv::Scalar(0, 0, 0), 1, cv::LINE_AA);
  io::write_png(path, image);
}

}  // namespace msislab::plot
