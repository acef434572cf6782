// Figures of the sonar front end, drawn with OpenCV and written as PNG (atomically): a map of scan
// points placed in the world with the trajectories, and one scan before and after motion
// compensation (paper Fig. 2a).
#pragma once

#include <Eigen/Core>
#include <string>
#include <vector>

namespace msislab::plot {

struct Track {
  std::string label;
  std::vector<Eigen::Vector2d> points_m;
  int bgr = 0x0000ff;  ///< colour as 0xBBGGRR
};

/// Points (grey) and tracks in the world frame, north up, with a 50 m scale bar and a legend.
void write_map_png(const std::string& path, const std::string& title,
                   const std::vector<Eigen::Vector2d>& points_m, const std::vector<Track>& tracks,
                   int width_px = 900);

/// Two panels in the scan frame (forward up, port left), same scale: before and after.
void write_scan_comparison_png(const std::string& path, const std::string& title,
                               const std::vector<Eigen::Vector2d>& before_m,
                               const std::vector<Eigen::Vector2d>& after_m);

}  // namespace msislab::plot
