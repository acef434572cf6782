#include "plot/acoustic_image.hpp"

#include <algorithm>
#include <cmath>
#include <opencv2/core.hpp>
#include <opencv2/imgproc.hpp>

#include "geometry/se2.hpp"
#include "io/input_error.hpp"
#include "io/png_file.hpp"

namespace msislab::plot {

namespace {
/// For every transducer step, the beam drawn there (the last one of the revolution), or -1.
std::vector<int> beams_by_step(const std::vector<io::SonarBeamRecord>& beams, int steps,
                               double step_rad) {
  std::vector<int> by_step(static_cast<std::size_t>(steps), -1);
  for (std::size_t i = 0; i < beams.size(); ++i) {
    long step = std::lround(beams[i].transducer_angle_rad / step_rad) % steps;
    if (step < 0) step += steps;
    by_step[static_cast<std::size_t>(step)] = static_cast<int>(i);
  }
  return by_step;
}

/// Line thickness in pixels for a drawing scale (1 at the reference size).
int thickness(double scale, int reference = 1) {
  return std::max(1, static_cast<int>(std::lround(reference * scale)));
}

/// Range rings with their labels and the forward arrow; text and lines scale with the image
/// (1 at 800 px, the default of msislab image).
void draw_range_rings(cv::Mat& image, double px_per_m, double range_m) {
  const double scale = image.rows / 800.0;
  const cv::Point centre(image.cols / 2, image.rows / 2);
  const double ring_m = range_m > 30.0 ? 10.0 : 5.0;
  const auto px = [&](double reference) {
    return static_cast<int>(std::lround(reference * scale));
  };
  for (double r = ring_m; r <= range_m + 1e-9; r += ring_m) {
    const int radius = static_cast<int>(std::lround(r * px_per_m));
    cv::circle(image, centre, radius, cv::Scalar(90, 160, 90), thickness(scale), cv::LINE_AA);
    cv::putText(image, std::to_string(static_cast<int>(r)) + " m",
                centre + cv::Point(px(4), -radius + px(14)), cv::FONT_HERSHEY_SIMPLEX, 0.45 * scale,
                cv::Scalar(120, 220, 120), thickness(scale), cv::LINE_AA);
  }
  cv::arrowedLine(image, centre, centre + cv::Point(0, -px(40)), cv::Scalar(255, 255, 255),
                  thickness(scale, 2), cv::LINE_AA, 0, 0.3);
  cv::putText(image, "forward", centre + cv::Point(px(6), -px(30)), cv::FONT_HERSHEY_SIMPLEX,
              0.45 * scale, cv::Scalar(255, 255, 255), thickness(scale), cv::LINE_AA);
}

/// The fan, size_px x size_px, coloured and with its range rings.
cv::Mat draw_fan(const std::vector<io::SonarBeamRecord>& beams, const io::SonarSetup& setup,
                 const SonarMount& mount, int size_px, const std::string& path) {
  if (beams.empty()) io::fail_file(path, "no sonar beams to draw");
  const int steps = static_cast<int>(std::lround(2.0 * M_PI / setup.step_rad));
  const std::vector<int> by_step = beams_by_step(beams, steps, setup.step_rad);
  const double px_per_m = 0.5 * size_px / setup.range_m;
  cv::Mat gray(size_px, size_px, CV_8UC1, cv::Scalar(0));
  for (int row = 0; row < size_px; ++row) {
    for (int col = 0; col < size_px; ++col) {
      // Pixel -> vehicle frame: up is forward (+x), left is port (+y).
      const double x_m = (size_px / 2.0 - row) / px_per_m;
      const double y_m = (size_px / 2.0 - col) / px_per_m;
      const double range_m = std::hypot(x_m, y_m);
      if (range_m > setup.range_m) continue;
      const double angle_rad =
          (std::atan2(y_m, x_m) - mount.bearing_offset_rad) / mount.bearing_sign;
      long step = std::lround(normalize_angle(angle_rad) / setup.step_rad) % steps;
      if (step < 0) step += steps;
      const int beam = by_step[static_cast<std::size_t>(step)];
      const long bin = std::lround(range_m / setup.bin_m) - 1;
      if (beam < 0 || bin < 0) continue;
      const auto& intensity = beams[static_cast<std::size_t>(beam)].intensity;
      if (bin < static_cast<long>(intensity.size())) {
        gray.at<std::uint8_t>(row, col) = intensity[static_cast<std::size_t>(bin)];
      }
    }
  }
  cv::Mat image;
  cv::applyColorMap(gray, image, cv::COLORMAP_INFERNO);
  draw_range_rings(image, px_per_m, setup.range_m);
  return image;
}

/// The inferno colour bar from 0 (bottom) to 255 (top) with its ticks, at `box`.
void draw_colour_bar(cv::Mat& canvas, const cv::Rect& box, double text_scale) {
  cv::Mat ramp(box.height, 1, CV_8UC1);
  for (int row = 0; row < box.height; ++row) {
    ramp.at<std::uint8_t>(row, 0) =
        static_cast<std::uint8_t>(std::lround(255.0 * (box.height - 1 - row) / (box.height - 1)));
  }
  cv::Mat coloured;
  cv::applyColorMap(ramp, coloured, cv::COLORMAP_INFERNO);
  cv::resize(coloured, canvas(box), box.size(), 0, 0, cv::INTER_NEAREST);
  cv::rectangle(canvas, box, cv::Scalar(0, 0, 0), 1);
  const cv::Scalar black(0, 0, 0);
  for (const int value : {0, 64, 128, 192, 255}) {
    const int y = box.y + box.height - 1 - (box.height - 1) * value / 255;
    cv::line(canvas, {box.x + box.width, y}, {box.x + box.width + 6, y}, black, 1);
    cv::putText(canvas, std::to_string(value),
                {box.x + box.width + 10, y + static_cast<int>(6 * text_scale)},
                cv::FONT_HERSHEY_SIMPLEX, 0.55 * text_scale, black, thickness(text_scale),
                cv::LINE_AA);
  }
  cv::putText(canvas, "echo", {box.x - 4, box.y - static_cast<int>(34 * text_scale)},
              cv::FONT_HERSHEY_SIMPLEX, 0.6 * text_scale, black, thickness(text_scale),
              cv::LINE_AA);
  cv::putText(canvas, "intensity", {box.x - 4, box.y - static_cast<int>(12 * text_scale)},
              cv::FONT_HERSHEY_SIMPLEX, 0.6 * text_scale, black, thickness(text_scale),
              cv::LINE_AA);
}

}  // namespace

void write_acoustic_image(const std::string& path, const std::vector<io::SonarBeamRecord>& beams,
                          const io::SonarSetup& setup, const SonarMount& mount, int size_px) {
  io::write_png(path, draw_fan(beams, setup, mount, size_px, path));
}

void write_acoustic_figure(const std::string& path, const std::vector<io::SonarBeamRecord>& beams,
                           const io::SonarSetup& setup, const SonarMount& mount,
                           const std::string& title, int width_px, int height_px) {
  const double scale = height_px / 900.0;
  const int top = static_cast<int>(100 * scale), bottom = static_cast<int>(20 * scale);
  const int bar_area = static_cast<int>(170 * scale);
  const int fan_px = std::min(height_px - top - bottom, width_px - bar_area - 20);
  cv::Mat canvas(height_px, width_px, CV_8UC3, cv::Scalar(255, 255, 255));
  const int fan_x = (width_px - bar_area - fan_px) / 2;
  // Only the disc of the fan: the corners beyond the range stay white.
  cv::Mat disc(fan_px, fan_px, CV_8UC1, cv::Scalar(0));
  cv::circle(disc, {fan_px / 2, fan_px / 2}, fan_px / 2 + 1, cv::Scalar(255), cv::FILLED);
  draw_fan(beams, setup, mount, fan_px, path)
      .copyTo(canvas(cv::Rect(fan_x, top, fan_px, fan_px)), disc);
  const cv::Rect bar(fan_x + fan_px + static_cast<int>(50 * scale), top + fan_px / 5,
                     static_cast<int>(30 * scale), fan_px * 3 / 5);
  draw_colour_bar(canvas, bar, scale);
  const cv::Scalar black(0, 0, 0);
  int baseline = 0;
  const cv::Size title_size =
      cv::getTextSize(title, cv::FONT_HERSHEY_SIMPLEX, 1.0 * scale, thickness(scale, 2), &baseline);
  cv::putText(canvas, title, {(width_px - title_size.width) / 2, static_cast<int>(45 * scale)},
              cv::FONT_HERSHEY_SIMPLEX, 1.0 * scale, black, thickness(scale, 2), cv::LINE_AA);
  const std::string caption = "vehicle frame, forward up and port left; range rings in metres";
  const cv::Size caption_size =
      cv::getTextSize(caption, cv::FONT_HERSHEY_SIMPLEX, 0.6 * scale, thickness(scale), &baseline);
  cv::putText(canvas, caption, {(width_px - caption_size.width) / 2, static_cast<int>(80 * scale)},
              cv::FONT_HERSHEY_SIMPLEX, 0.6 * scale, black, thickness(scale), cv::LINE_AA);
  io::write_png(path, canvas);
}

}  // namespace msislab::plot
