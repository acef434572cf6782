// msislab_make_stpere_marina: traces the St. Pere marina from the real sonar detections and writes
// it as a scene mesh (docs/scenes.md). The first detection of every beam is projected with the
// GPS position and MTi heading, rasterised into wall cells; the water is the area the beams swept,
// bounded by the walls and connected to the GPS track; its outline, simplified, is extruded to
// walls with a flat bottom.
#include <CLI/CLI.hpp>
#include <Eigen/Core>
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <iomanip>
#include <iostream>
#include <map>
#include <opencv2/core.hpp>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>
#include <stdexcept>
#include <string>
#include <vector>

#include "io/dataset.hpp"
#include "io/detections.hpp"
#include "io/mesh_io.hpp"
#include "sim/polygon_triangulation.hpp"
#include "slam/calibration.hpp"
#include "slam/evaluation.hpp"
#include "slam/navigation.hpp"
#include "slam/se2.hpp"

namespace {

using msislab::Pose2;
using Polygon = std::vector<Eigen::Vector2d>;

struct Options {
  std::string dataset_dir;
  std::string out_path;
  std::string preview_path;
  double depth_m = 1.5;         ///< vehicle depth of the replica scenario, m
  double bottom_below_m = 1.8;  ///< bottom below the vehicle, m
  double wall_top_m = 1.0;      ///< walls rise this far above the surface, m
  double cell_m = 0.5;          ///< raster cell, m
  int min_hits = 2;             ///< first detections a cell needs to count as wall
  double simplify_m = 0.75;     ///< outline simplification tolerance (approxPolyDP), m
  int min_wall_cells = 30;      ///< smaller connected pieces of wall cells are dropped as noise
  double max_track_distance_m = 30.0;  ///< water lies within this distance of the GPS track, m
  double wall_support_m = 1.5;  ///< an outline farther than this from any wall is at a gap, m
  double min_width_m = 3.0;     ///< water slivers narrower than this are cut, m
  double wall_offset_m = 1.0;   ///< the outline lies this far into the band of wall cells, m
};

/// The first (nearest) detection of one beam, in the world frame.
struct BeamEcho {
  Eigen::Vector2d head_world_m = Eigen::Vector2d::Zero();
  Eigen::Vector2d echo_world_m = Eigen::Vector2d::Zero();
};

/// The raster: cell (col, row) covers x_min + col * cell .. +cell, y_max - row * cell .. -cell.
struct Grid {
  double x_min_m = 0.0;
  double y_max_m = 0.0;
  double cell_m = 0.5;
  int cols = 0;
  int rows = 0;
  cv::Size size() const { return {cols, rows}; }
  cv::Point pixel(const Eigen::Vector2d& p_m) const {
    return {static_cast<int>(std::floor((p_m.x() - x_min_m) / cell_m)),
            static_cast<int>(std::floor((y_max_m - p_m.y()) / cell_m))};
  }
  Eigen::Vector2d world(const cv::Point& px) const {
    return {x_min_m + (px.x + 0.5) * cell_m, y_max_m - (px.y + 0.5) * cell_m};
  }
};

std::vector<msislab::io::DetectionRecord> first_detections(
    const std::vector<msislab::io::DetectionRecord>& rows) {
  std::vector<msislab::io::DetectionRecord> first;
  for (const msislab::io::DetectionRecord& row : rows) {
    if (first.empty() || first.back().beam_row != row.beam_row) {
      first.push_back(row);
    } else if (row.range_m < first.back().range_m) {
      first.back() = row;
    }
  }
  return first;
}

/// GPS fixes as a trajectory for interpolate_pose (positions only; yaw unused).
std::vector<msislab::StampedPose> gps_track(const std::vector<msislab::PositionFix>& fixes) {
  std::vector<msislab::StampedPose> track;
  for (const msislab::PositionFix& fix : fixes) {
    msislab::StampedPose pose;
    pose.t_s = fix.t_s;
    pose.pose.mean = Pose2(fix.p_world_m.x(), fix.p_world_m.y(), 0.0);
    track.push_back(pose);
  }
  return track;
}

/// Point = T_world_vehicle (+) T_vehicle_beam (+) [range, 0], for beams inside the GPS time span.
std::vector<BeamEcho> project_first_echoes(const std::vector<msislab::io::DetectionRecord>& first,
                                           const std::vector<msislab::StampedPose>& track,
                                           const msislab::NavigationLog& navigation,
                                           const msislab::SonarMount& mount) {
  std::vector<BeamEcho> echoes;
  for (const msislab::io::DetectionRecord& d : first) {
    if (d.t_log_s < track.front().t_s || d.t_log_s > track.back().t_s) continue;
    const Eigen::Vector2d p_world_m = msislab::interpolate_pose(track, d.t_log_s).translation();
    const double yaw_rad = msislab::nearest_heading(navigation.heading, d.t_log_s).yaw_rad;
    const Pose2 T_world_vehicle(p_world_m.x(), p_world_m.y(), yaw_rad);
    const Pose2 T_vehicle_beam(mount.x_m, mount.y_m,
                               msislab::sonar_bearing_in_vehicle(d.angle_rad, mount));
    const Pose2 T_world_beam = T_world_vehicle + T_vehicle_beam;
    echoes.push_back(
        {T_world_beam.translation(), T_world_beam.transform(Eigen::Vector2d(d.range_m, 0.0))});
  }
  return echoes;
}

Grid grid_around(const std::vector<BeamEcho>& echoes, double cell_m, double margin_m) {
  Eigen::Vector2d lo = echoes.front().echo_world_m;
  Eigen::Vector2d hi = lo;
  for (const BeamEcho& e : echoes) {
    for (const Eigen::Vector2d& p : {e.echo_world_m, e.head_world_m}) {
      lo = lo.cwiseMin(p);
      hi = hi.cwiseMax(p);
    }
  }
  Grid grid;
  grid.cell_m = cell_m;
  grid.x_min_m = std::floor((lo.x() - margin_m) / cell_m) * cell_m;
  grid.y_max_m = std::ceil((hi.y() + margin_m) / cell_m) * cell_m;
  grid.cols = static_cast<int>(std::ceil((hi.x() - lo.x() + 2.0 * margin_m) / cell_m));
  grid.rows = static_cast<int>(std::ceil((hi.y() - lo.y() + 2.0 * margin_m) / cell_m));
  return grid;
}

/// Cells holding at least min_hits first detections, closed (3x3) to join the wall pixels, in
/// connected pieces of at least min_cells (isolated echoes dropped).
cv::Mat wall_cells(const std::vector<BeamEcho>& echoes, const Grid& grid, const Options& options) {
  cv::Mat hits = cv::Mat::zeros(grid.size(), CV_32S);
  for (const BeamEcho& e : echoes) ++hits.at<int>(grid.pixel(e.echo_world_m));
  cv::Mat walls = hits >= options.min_hits;
  cv::morphologyEx(walls, walls, cv::MORPH_CLOSE,
                   cv::getStructuringElement(cv::MORPH_ELLIPSE, cv::Size(3, 3)));
  cv::Mat labels, stats, centroids;
  const int count = cv::connectedComponentsWithStats(walls, labels, stats, centroids, 8, CV_32S);
  for (int label = 1; label < count; ++label) {
    if (stats.at<int>(label, cv::CC_STAT_AREA) < options.min_wall_cells) {
      walls.setTo(0, labels == label);
    }
  }
  return walls;
}

/// Cells crossed by some beam between the head and 1 m short of its first detection, closed (5x5)
/// to fill the gaps between diverging beams: the water the sonar saw.
cv::Mat swept_cells(const std::vector<BeamEcho>& echoes, const Grid& grid) {
  cv::Mat swept = cv::Mat::zeros(grid.size(), CV_8U);
  constexpr double kShortOfEchoM = 1.0;
  for (const BeamEcho& e : echoes) {
    const Eigen::Vector2d ray_m = e.echo_world_m - e.head_world_m;
    const double length_m = ray_m.norm();
    if (length_m <= kShortOfEchoM) continue;
    const Eigen::Vector2d end_m = e.head_world_m + ray_m * (1.0 - kShortOfEchoM / length_m);
    cv::line(swept, grid.pixel(e.head_world_m), grid.pixel(end_m), 255, 1, cv::LINE_8);
  }
  cv::morphologyEx(swept, swept, cv::MORPH_CLOSE,
                   cv::getStructuringElement(cv::MORPH_ELLIPSE, cv::Size(5, 5)));
  return swept;
}

/// Cells within max_distance_m of the GPS track.
cv::Mat near_track_cells(const std::vector<msislab::PositionFix>& gps, const Grid& grid,
                         double max_distance_m) {
  cv::Mat off_track(grid.size(), CV_8U, cv::Scalar(255));
  std::vector<cv::Point> track_px;
  for (const msislab::PositionFix& fix : gps) track_px.push_back(grid.pixel(fix.p_world_m));
  cv::polylines(off_track, track_px, false, cv::Scalar(0), 1, cv::LINE_8);
  cv::Mat distance_cells;
  cv::distanceTransform(off_track, distance_cells, cv::DIST_L2, cv::DIST_MASK_PRECISE);
  return distance_cells <= max_distance_m / grid.cell_m;
}

/// Swept, non-wall cells within reach of the track, flood-filled (4-neighbourhood, so 8-connected
/// wall lines hold) from where the track spends most of its fixes.
cv::Mat flood_from_track(const cv::Mat& walls, const cv::Mat& swept,
                         const std::vector<msislab::PositionFix>& gps, const Grid& grid,
                         double max_track_distance_m) {
  const cv::Mat free_cells = swept & ~walls & near_track_cells(gps, grid, max_track_distance_m);
  cv::Mat labels;
  cv::connectedComponents(free_cells, labels, 4, CV_32S);
  std::map<int, int> fixes_per_label;
  for (const msislab::PositionFix& fix : gps) {
    const int label = labels.at<int>(grid.pixel(fix.p_world_m));
    if (label > 0) ++fixes_per_label[label];
  }
  if (fixes_per_label.empty()) throw std::runtime_error("the GPS track lies on no free cell");
  const auto most =
      std::max_element(fixes_per_label.begin(), fixes_per_label.end(),
                       [](const auto& a, const auto& b) { return a.second < b.second; });
  return labels == most->first;
}

std::vector<cv::Point> largest_outline(const cv::Mat& mask) {
  std::vector<std::vector<cv::Point>> contours;
  cv::findContours(mask.clone(), contours, cv::RETR_EXTERNAL, cv::CHAIN_APPROX_NONE);
  if (contours.empty()) throw std::runtime_error("no water region connected to the GPS track");
  return *std::max_element(contours.begin(), contours.end(), [](const auto& a, const auto& b) {
    return cv::contourArea(a) < cv::contourArea(b);
  });
}

/// Distance (m) from every cell to the nearest wall cell.
cv::Mat wall_distance_m(const cv::Mat& walls, double cell_m) {
  cv::Mat distance_cells;
  cv::distanceTransform(~walls, distance_cells, cv::DIST_L2, cv::DIST_MASK_PRECISE);
  return distance_cells * cell_m;
}

/// The wall cell nearest to px within radius_cells (px itself when there is none).
cv::Point nearest_wall_cell(const cv::Mat& walls, const cv::Point& px, int radius_cells) {
  cv::Point nearest = px;
  int best_squared = radius_cells * radius_cells + 1;
  for (int dy = -radius_cells; dy <= radius_cells; ++dy) {
    for (int dx = -radius_cells; dx <= radius_cells; ++dx) {
      const cv::Point q = px + cv::Point(dx, dy);
      const int squared = dx * dx + dy * dy;
      if (squared < best_squared && q.inside(cv::Rect({0, 0}, walls.size())) &&
          walls.at<std::uint8_t>(q) != 0) {
        nearest = q;
        best_squared = squared;
      }
    }
  }
  return nearest;
}

/// Where an outline leaves the walls (beams went through a gap, or saw nothing within range),
/// the straight line between the walls at the last outline point near a wall and the next one.
std::vector<std::pair<cv::Point, cv::Point>> gap_closures(const std::vector<cv::Point>& outline,
                                                          const cv::Mat& walls, double cell_m,
                                                          double wall_support_m) {
  const cv::Mat distance_m = wall_distance_m(walls, cell_m);
  const int support_cells = static_cast<int>(std::ceil(wall_support_m / cell_m));
  const auto on_wall = [&](std::size_t i) {
    return distance_m.at<float>(outline[i % outline.size()]) <= wall_support_m;
  };
  const auto wall_at = [&](std::size_t i) {
    return nearest_wall_cell(walls, outline[i % outline.size()], support_cells);
  };
  std::size_t start = 0;
  while (start < outline.size() && !on_wall(start)) ++start;
  std::vector<std::pair<cv::Point, cv::Point>> closures;
  if (start == outline.size()) return closures;
  std::size_t last_on_wall = start;
  for (std::size_t i = start + 1; i <= start + outline.size(); ++i) {
    if (!on_wall(i)) continue;
    if (i - last_on_wall > 1) closures.emplace_back(wall_at(last_on_wall), wall_at(i));
    last_on_wall = i;
  }
  return closures;
}

/// The largest region of a mask, its holes filled.
cv::Mat fill_largest(const cv::Mat& mask) {
  std::vector<std::vector<cv::Point>> outlines = {largest_outline(mask)};
  cv::Mat filled = cv::Mat::zeros(mask.size(), CV_8U);
  cv::drawContours(filled, outlines, -1, 255, cv::FILLED);
  return filled;
}

/// The water: flooded from the track inside the walls (a); where its outline leaves the walls,
/// straight closure lines that bound a second flood (b); the unswept notches between a closure
/// line and the water filled (c).
cv::Mat water_cells(const cv::Mat& walls, const std::vector<BeamEcho>& echoes,
                    const std::vector<msislab::PositionFix>& gps, const Grid& grid,
                    const Options& options) {
  const cv::Mat swept = swept_cells(echoes, grid);
  const cv::Mat first_water =
      flood_from_track(walls, swept, gps, grid, options.max_track_distance_m);  // (a)
  const auto closures =
      gap_closures(largest_outline(first_water), walls, grid.cell_m, options.wall_support_m);
  cv::Mat closed_walls = walls.clone();
  for (const auto& [a, b] : closures) cv::line(closed_walls, a, b, 255, 1, cv::LINE_8);
  cv::Mat water = flood_from_track(closed_walls, swept, gps, grid, options.max_track_distance_m);
  for (const auto& [a, b] : closures) cv::line(water, a, b, 255, 1, cv::LINE_8);  // (b)
  return fill_largest(water);                                                     // (c)
}

/// Slivers of water narrower than min_width_m (into the smeared walls) cut (a); the water grown
/// into the band of wall cells by wall_offset_m, so that the outline runs through the detections
/// rather than along their inner edge (b); one-cell notches closed (c).
cv::Mat settle_on_walls(cv::Mat water, const cv::Mat& walls, double cell_m,
                        const Options& options) {
  const int width_cells = 2 * static_cast<int>(std::lround(options.min_width_m / 2.0 / cell_m)) + 1;
  cv::morphologyEx(
      water, water, cv::MORPH_OPEN,
      cv::getStructuringElement(cv::MORPH_ELLIPSE, cv::Size(width_cells, width_cells)));
  water = fill_largest(water);  // (a)
  const int offset_cells = static_cast<int>(std::lround(options.wall_offset_m / cell_m));
  const cv::Mat step = cv::getStructuringElement(cv::MORPH_RECT, cv::Size(3, 3));
  cv::Mat grown;
  for (int i = 0; i < offset_cells; ++i) {
    cv::dilate(water, grown, step);
    water |= grown & walls;  // (b)
  }
  cv::morphologyEx(water, water, cv::MORPH_CLOSE,
                   cv::getStructuringElement(cv::MORPH_ELLIPSE, cv::Size(5, 5)));  // (c)
  return water;
}

/// The outline of the water, simplified, counter-clockwise in the world frame.
Polygon outline_polygon(const cv::Mat& water, const Grid& grid, double simplify_m) {
  std::vector<cv::Point> simplified;
  cv::approxPolyDP(largest_outline(water), simplified, simplify_m / grid.cell_m, true);
  Polygon polygon;
  for (const cv::Point& px : simplified) polygon.push_back(grid.world(px));
  if (msislab::sim::signed_double_area(polygon) < 0.0) std::reverse(polygon.begin(), polygon.end());
  return polygon;
}

/// Whether edge i (vertex i to i + 1) was closed by assumption: its middle is far from the walls.
std::vector<bool> assumed_edges(const Polygon& polygon, const cv::Mat& distance_m, const Grid& grid,
                                const Options& options) {
  std::vector<bool> assumed;
  for (std::size_t i = 0; i < polygon.size(); ++i) {
    const Eigen::Vector2d middle_m = 0.5 * (polygon[i] + polygon[(i + 1) % polygon.size()]);
    assumed.push_back(distance_m.at<float>(grid.pixel(middle_m)) > options.wall_support_m);
  }
  return assumed;
}

/// Walls (quads from z_top to z_bottom along each edge, facing inward) and a flat bottom.
msislab::sim::TriangleMesh marina_mesh(const Polygon& ccw_polygon, double z_top_m,
                                       double z_bottom_m) {
  msislab::sim::TriangleMesh mesh;
  mesh.materials = {{"walls", 0.6f, 0.3f}, {"bottom", 0.3f, 0.2f}};
  mesh.group_names = {"walls", "bottom"};
  const int n = static_cast<int>(ccw_polygon.size());
  for (const Eigen::Vector2d& p : ccw_polygon) {
    mesh.vertices_m.emplace_back(static_cast<float>(p.x()), static_cast<float>(p.y()),
                                 static_cast<float>(z_top_m));
    mesh.vertices_m.emplace_back(static_cast<float>(p.x()), static_cast<float>(p.y()),
                                 static_cast<float>(z_bottom_m));
  }
  for (int i = 0; i < n; ++i) {
    const int a_top = 2 * i, a_bottom = 2 * i + 1;
    const int b_top = 2 * ((i + 1) % n), b_bottom = b_top + 1;
    // Counter-clockwise seen from the polygon's inside (its left): the normals face the water.
    mesh.triangles.emplace_back(a_bottom, b_top, b_bottom);
    mesh.triangles.emplace_back(a_bottom, a_top, b_top);
    mesh.material_ids.insert(mesh.material_ids.end(), 2, 0u);
  }
  for (const Eigen::Vector3i& t : msislab::sim::triangulate_polygon(ccw_polygon)) {
    mesh.triangles.emplace_back(2 * t[0] + 1, 2 * t[1] + 1, 2 * t[2] + 1);
    mesh.material_ids.push_back(1u);
  }
  return mesh;
}

void write_preview(const std::string& path, const std::vector<BeamEcho>& echoes,
                   const std::vector<msislab::PositionFix>& gps, const Polygon& polygon,
                   const std::vector<bool>& assumed, const Grid& grid) {
  constexpr int kScale = 2;      // image pixels per cell
  constexpr int kLegendPx = 60;  // band above the map for the legend
  cv::Mat image(grid.rows * kScale + kLegendPx, grid.cols * kScale, CV_8UC3,
                cv::Scalar(255, 255, 255));
  const auto to_image = [&](const Eigen::Vector2d& p_m) {
    return cv::Point(static_cast<int>((p_m.x() - grid.x_min_m) / grid.cell_m * kScale),
                     kLegendPx + static_cast<int>((grid.y_max_m - p_m.y()) / grid.cell_m * kScale));
  };
  for (const BeamEcho& e : echoes) {
    cv::circle(image, to_image(e.echo_world_m), 0, cv::Scalar(110, 110, 110), cv::FILLED);
  }
  std::vector<cv::Point> track_px;
  for (const msislab::PositionFix& fix : gps) track_px.push_back(to_image(fix.p_world_m));
  cv::polylines(image, track_px, false, cv::Scalar(200, 120, 0), 1, cv::LINE_AA);
  for (std::size_t i = 0; i < polygon.size(); ++i) {
    const cv::Scalar colour = assumed[i] ? cv::Scalar(0, 150, 255) : cv::Scalar(0, 0, 220);
    cv::line(image, to_image(polygon[i]), to_image(polygon[(i + 1) % polygon.size()]), colour, 2,
             cv::LINE_AA);
    cv::circle(image, to_image(polygon[i]), 3, cv::Scalar(0, 0, 220), cv::FILLED);
  }
  const int bar_px = static_cast<int>(50.0 / grid.cell_m * kScale);
  const cv::Point bar_start(20, image.rows - 20);
  cv::line(image, bar_start, bar_start + cv::Point(bar_px, 0), cv::Scalar(0, 0, 0), 3);
  const auto text = [&](const std::string& line, cv::Point at) {
    cv::putText(image, line, at, cv::FONT_HERSHEY_SIMPLEX, 0.6, cv::Scalar(0, 0, 0), 1,
                cv::LINE_AA);
  };
  text("50 m", bar_start + cv::Point(bar_px / 2 - 20, -10));
  text("North up. grey: first detections, blue: GPS track,", cv::Point(10, 22));
  text("red: outline on walls, orange: closed by assumption", cv::Point(10, 46));
  if (!cv::imwrite(path, image)) throw std::runtime_error("cannot write " + path);
}

void print_summary(const Polygon& polygon, const std::vector<bool>& assumed,
                   const msislab::sim::TriangleMesh& mesh, std::size_t echo_count) {
  Eigen::Vector2d lo = polygon.front();
  Eigen::Vector2d hi = lo;
  for (const Eigen::Vector2d& p : polygon) {
    lo = lo.cwiseMin(p);
    hi = hi.cwiseMax(p);
  }
  std::cout << std::fixed << std::setprecision(1) << "first detections projected: " << echo_count
            << "\npolygon: " << polygon.size() << " vertices, area "
            << 0.5 * msislab::sim::signed_double_area(polygon) << " m^2, bbox x [" << lo.x() << ", "
            << hi.x() << "] y [" << lo.y() << ", " << hi.y() << "] m (" << hi.x() - lo.x() << " x "
            << hi.y() - lo.y() << " m)\n";
  for (std::size_t i = 0; i < polygon.size(); ++i) {
    if (!assumed[i]) continue;
    const Eigen::Vector2d& a = polygon[i];
    const Eigen::Vector2d& b = polygon[(i + 1) % polygon.size()];
    std::cout << "closed by assumption (no wall seen): (" << a.x() << ", " << a.y() << ") to ("
              << b.x() << ", " << b.y() << "), " << (b - a).norm() << " m\n";
  }
  std::cout << "mesh: " << mesh.vertices_m.size() << " vertices, " << mesh.triangles.size()
            << " triangles\n";
}

void make_marina(const Options& options) {
  namespace io = msislab::io;
  const io::DatasetFiles files = io::find_dataset_files(options.dataset_dir);
  if (!files.detections) {
    throw std::runtime_error(options.dataset_dir + ": no *_detections.csv[.gz]");
  }
  const msislab::Calibration calibration = io::load_calibration(files);
  const msislab::NavigationLog navigation = io::load_navigation(files, calibration);
  const std::vector<msislab::PositionFix> gps = io::load_gps_fixes(files, calibration);
  const std::vector<BeamEcho> echoes =
      project_first_echoes(first_detections(io::read_detections(*files.detections)), gps_track(gps),
                           navigation, calibration.sonar);
  if (echoes.empty()) throw std::runtime_error("no detection inside the GPS time span");

  const Grid grid = grid_around(echoes, options.cell_m, 5.0);
  const cv::Mat walls = wall_cells(echoes, grid, options);
  const cv::Mat water =
      settle_on_walls(water_cells(walls, echoes, gps, grid, options), walls, grid.cell_m, options);
  const Polygon polygon = outline_polygon(water, grid, options.simplify_m);
  if (const auto crossing = msislab::sim::find_crossing_edges(polygon)) {
    throw std::runtime_error("the simplified outline crosses itself (edges " +
                             std::to_string(crossing->first) + " and " +
                             std::to_string(crossing->second) + "); try a smaller --simplify");
  }
  const cv::Mat distance_m = wall_distance_m(walls, grid.cell_m);
  const std::vector<bool> assumed = assumed_edges(polygon, distance_m, grid, options);
  const msislab::sim::TriangleMesh mesh =
      marina_mesh(polygon, options.wall_top_m, -(options.depth_m + options.bottom_below_m));
  io::write_obj(options.out_path, mesh);
  if (!options.preview_path.empty()) {
    write_preview(options.preview_path, echoes, gps, polygon, assumed, grid);
  }
  print_summary(polygon, assumed, mesh, echoes.size());
  std::cout << "wrote " << options.out_path << "\n";
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"Trace the St. Pere marina from the real sonar detections into a scene mesh (OBJ)"};
  Options options;
  app.add_option("--dataset", options.dataset_dir, "St. Pere dataset directory")->required();
  app.add_option("--out", options.out_path, "Output OBJ")->required();
  app.add_option("--preview", options.preview_path, "Optional PNG: detections, track, outline");
  app.add_option("--depth", options.depth_m, "Vehicle depth, m")
      ->check(CLI::NonNegativeNumber)
      ->capture_default_str();
  app.add_option("--bottom-below", options.bottom_below_m, "Bottom below the vehicle, m")
      ->check(CLI::PositiveNumber)
      ->capture_default_str();
  app.add_option("--cell", options.cell_m, "Raster cell, m")
      ->check(CLI::Range(0.05, 5.0))
      ->capture_default_str();
  app.add_option("--min-hits", options.min_hits, "First detections a cell needs to be wall")
      ->check(CLI::PositiveNumber)
      ->capture_default_str();
  app.add_option("--simplify", options.simplify_m, "Outline tolerance (approxPolyDP), m")
      ->check(CLI::PositiveNumber)
      ->capture_default_str();
  app.add_option("--max-track-distance", options.max_track_distance_m,
                 "Water lies within this distance of the GPS track, m")
      ->check(CLI::PositiveNumber)
      ->capture_default_str();
  CLI11_PARSE(app, argc, argv);
  try {
    make_marina(options);
  } catch (const std::exception& e) {
    std::cerr << "msislab_make_stpere_marina: " << e.what() << "\n";
    return 2;
  }
  return 0;
}
