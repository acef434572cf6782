#include "io/acoustic_image.hpp"

#include <cmath>
#include <opencv2/core.hpp>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include "io/atomic_file.hpp"
#include "io/input_error.hpp"
#include "slam/se2.hpp"

namespace msislab::io {

namespace {
/// For every transducer step, the beam drawn there (the last one of the revolution), or -1.
std::vector<int> beams_by_step(const std::vector<SonarBeamRecord>& beams, int steps,
                               double step_rad) {
  std::vector<int> by_step(static_cast<std::size_t>(steps), -1);
  for (std::size_t i = 0; i < beams.size(); ++i) {
    long step = std::lround(beams[i].transducer_angle_rad / step_rad) % steps;
    if (step < 0) step += steps;
    by_step[static_cast<std::size_t>(step)] = static_cast<int>(i);
  }
  return by_step;
}

void draw_range_rings(cv::Mat& image, double px_per_m, double range_m) {
  const cv::Point centre(image.cols / 2, image.rows / 2);
  const double ring_m = range_m > 30.0 ? 10.0 : 5.0;
  for (double r = ring_m; r <= range_m + 1e-9; r += ring_m) {
    const int radius = static_cast<int>(std::lround(r * px_per_m));
    cv::circle(image, centre, radius, cv::Scalar(90, 160, 90), 1, cv::LINE_AA);
    cv::putText(image, std::to_string(static_cast<int>(r)) + " m",
                centre + cv::Point(4, -radius + 14), cv::FONT_HERSHEY_SIMPLEX, 0.45,
                cv::Scalar(120, 220, 120), 1, cv::LINE_AA);
  }
  cv::arrowedLine(image, centre, centre + cv::Point(0, -40), cv::Scalar(255, 255, 255), 2,
                  cv::LINE_AA, 0, 0.3);
  cv::putText(image, "forward", centre + cv::Point(6, -30), cv::FONT_HERSHEY_SIMPLEX, 0.45,
              cv::Scalar(255, 255, 255), 1, cv::LINE_AA);
}
}  // namespace

void write_acoustic_image(const std::string& path, const std::vector<SonarBeamRecord>& beams,
                          const SonarSetup& setup, const SonarMount& mount, int size_px) {
  if (beams.empty()) fail_file(path, "no sonar beams to draw");
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
  std::vector<std::uint8_t> png;
  if (!cv::imencode(".png", image, png)) fail_file(path, "PNG encoding failed");
  write_file_atomically(path, [&](std::ostream& out) {
    out.write(reinterpret_cast<const char*>(png.data()), static_cast<std::streamsize>(png.size()));
  });
}

}  // namespace msislab::io
