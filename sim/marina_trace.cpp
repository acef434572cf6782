#include "sim/marina_trace.hpp"

#include <algorithm>
#include <cmath>
#include <map>
#include <opencv2/core.hpp>
#include <opencv2/imgproc.hpp>
#include <set>
#include <stdexcept>

#include "sim/polygon_triangulation.hpp"

namespace msislab::sim {

Eigen::Vector2d TraceBeam::echo_world_m() const {
  return head_world_m +
         first_range_m * Eigen::Vector2d(std::cos(bearing_world_rad), std::sin(bearing_world_rad));
}

std::vector<Eigen::Vector2d> ClutterObject::ccw_footprint_m() const {
  const Eigen::Vector2d u(std::cos(yaw_rad), std::sin(yaw_rad));
  const Eigen::Vector2d v(-u.y(), u.x());
  const Eigen::Vector2d a = 0.5 * length_m * u, b = 0.5 * width_m * v;
  return {centre_m - a - b, centre_m + a - b, centre_m + a + b, centre_m - a + b};
}

namespace {

/// The raster: cell (col, row) covers x_min + col * cell .. +cell, y_max - row * cell .. -cell.
struct Grid {
  double x_min_m = 0.0;
  double y_max_m = 0.0;
  double cell_m = 0.25;
  int cols = 0;
  int rows = 0;
  cv::Size size() const { return {cols, rows}; }
  cv::Point pixel(const Eigen::Vector2d& p_m) const {
    return {static_cast<int>(std::floor((p_m.x() - x_min_m) / cell_m)),
            static_cast<int>(std::floor((y_max_m - p_m.y()) / cell_m))};
  }
  Eigen::Vector2d world(const cv::Point2f& px) const {
    return {x_min_m + (px.x + 0.5) * cell_m, y_max_m - (px.y + 0.5) * cell_m};
  }
  int cells(double length_m) const { return static_cast<int>(std::lround(length_m / cell_m)); }
};

Grid grid_around(const std::vector<TraceBeam>& beams, double cell_m, double reach_m) {
  Eigen::Vector2d lo = beams.front().head_world_m, hi = lo;
  for (const TraceBeam& b : beams) {
    lo = lo.cwiseMin(b.head_world_m);
    hi = hi.cwiseMax(b.head_world_m);
  }
  lo -= Eigen::Vector2d::Constant(reach_m + 2.0);
  hi += Eigen::Vector2d::Constant(reach_m + 2.0);
  Grid grid;
  grid.cell_m = cell_m;
  grid.x_min_m = std::floor(lo.x() / cell_m) * cell_m;
  grid.y_max_m = std::ceil(hi.y() / cell_m) * cell_m;
  grid.cols = static_cast<int>(std::ceil((hi.x() - grid.x_min_m) / cell_m));
  grid.rows = static_cast<int>(std::ceil((grid.y_max_m - lo.y()) / cell_m));
  return grid;
}

cv::Mat disc(int diameter_cells) {
  const int d = std::max(1, diameter_cells | 1);
  return cv::getStructuringElement(cv::MORPH_ELLIPSE, cv::Size(d, d));
}

/// Per cell: first detections (CV_32S) and the distinct revolutions they came from (CV_32S).
std::pair<cv::Mat, cv::Mat> echo_counts(const std::vector<TraceBeam>& beams, const Grid& grid) {
  cv::Mat hits = cv::Mat::zeros(grid.size(), CV_32S);
  cv::Mat revolutions = cv::Mat::zeros(grid.size(), CV_32S);
  cv::Mat last = cv::Mat(grid.size(), CV_32S, cv::Scalar(-1));
  for (const TraceBeam& b : beams) {
    if (b.first_range_m <= 0.0) continue;
    const cv::Point px = grid.pixel(b.echo_world_m());
    ++hits.at<int>(px);
    if (last.at<int>(px) != b.revolution) ++revolutions.at<int>(px);
    last.at<int>(px) = b.revolution;
  }
  return {hits, revolutions};
}

/// Cells with first detections whose 5x5 neighbourhood (1.25 m at 0.25 m cells) holds min_hits of
/// them from min_revolutions revolutions (a detection seen once, by one revolution, is dropped),
/// closed (3x3) to join them.
cv::Mat echo_cells(const cv::Mat& hits, const cv::Mat& revolutions,
                   const MarinaTraceConfig& config) {
  cv::Mat hits3, revolutions3;
  cv::boxFilter(hits, hits3, CV_32S, cv::Size(9, 9), cv::Point(-1, -1), false);
  cv::boxFilter(revolutions, revolutions3, CV_32S, cv::Size(9, 9), cv::Point(-1, -1), false);
  cv::Mat echoes =
      (hits > 0) & (hits3 >= config.min_hits) & (revolutions3 >= config.min_revolutions);
  cv::morphologyEx(echoes, echoes, cv::MORPH_CLOSE, disc(3));
  return echoes;
}

/// The cells the beams crossed: a detected beam up to short_of_echo_m before its echo, a beam
/// that detected nothing up to max_range_m or the first cell within 1 m of any detection (a wall
/// too sparse to be traced still stops it); closed (gaps between diverging beams).
cv::Mat swept_cells(const std::vector<TraceBeam>& beams, const cv::Mat& hits, const Grid& grid,
                    const MarinaTraceConfig& config) {
  cv::Mat blocked;
  cv::dilate(hits > 0, blocked, disc(grid.cells(2.0)));
  cv::Mat swept = cv::Mat::zeros(grid.size(), CV_8U);
  for (const TraceBeam& b : beams) {
    const Eigen::Vector2d dir(std::cos(b.bearing_world_rad), std::sin(b.bearing_world_rad));
    const bool detected = b.first_range_m > 0.0;
    const double reach_m = detected ? b.first_range_m - config.short_of_echo_m : config.max_range_m;
    if (reach_m <= 0.0) continue;
    cv::LineIterator line(swept, grid.pixel(b.head_world_m),
                          grid.pixel(b.head_world_m + reach_m * dir), 8);
    for (int i = 0; i < line.count; ++i, ++line) {
      if (!detected && blocked.at<std::uint8_t>(line.pos()) != 0) break;
      **line = 255;
    }
  }
  const double spacing_m = config.max_range_m * 2.0 * M_PI / 200.0;  // beams 1.8 deg apart
  cv::morphologyEx(swept, swept, cv::MORPH_CLOSE, disc(grid.cells(spacing_m) + 1));
  return swept;
}

std::vector<cv::Point> largest_outline(const cv::Mat& mask) {
  std::vector<std::vector<cv::Point>> contours;
  cv::findContours(mask.clone(), contours, cv::RETR_EXTERNAL, cv::CHAIN_APPROX_NONE);
  if (contours.empty()) throw std::runtime_error("no water region holds the track");
  return *std::max_element(contours.begin(), contours.end(), [](const auto& a, const auto& b) {
    return cv::contourArea(a) < cv::contourArea(b);
  });
}

/// The largest region of a mask, its holes filled.
cv::Mat fill_largest(const cv::Mat& mask) {
  const std::vector<std::vector<cv::Point>> outlines = {largest_outline(mask)};
  cv::Mat filled = cv::Mat::zeros(mask.size(), CV_8U);
  cv::drawContours(filled, outlines, -1, 255, cv::FILLED);
  return filled;
}

/// Swept, non-wall cells within reach of the track, flood-filled (4-neighbourhood, so 8-connected
/// wall lines hold) from the piece that holds most track points, its holes filled.
cv::Mat flood_from_track(const cv::Mat& walls, const cv::Mat& swept,
                         const std::vector<Eigen::Vector2d>& track_m, const Grid& grid,
                         double max_track_distance_m) {
  cv::Mat off_track(grid.size(), CV_8U, cv::Scalar(255));
  std::vector<cv::Point> track_px;
  for (const Eigen::Vector2d& p : track_m) track_px.push_back(grid.pixel(p));
  cv::polylines(off_track, track_px, false, cv::Scalar(0), 1, cv::LINE_8);
  cv::Mat distance_cells;
  cv::distanceTransform(off_track, distance_cells, cv::DIST_L2, cv::DIST_MASK_PRECISE);
  const cv::Mat free_cells =
      swept & ~walls & (distance_cells <= max_track_distance_m / grid.cell_m);
  cv::Mat labels;
  cv::connectedComponents(free_cells, labels, 4, CV_32S);
  std::map<int, int> points_per_label;
  for (const cv::Point& px : track_px) {
    if (px.inside(cv::Rect({0, 0}, grid.size())) && labels.at<int>(px) > 0) {
      ++points_per_label[labels.at<int>(px)];
    }
  }
  if (points_per_label.empty()) throw std::runtime_error("the track lies on no swept cell");
  const auto most =
      std::max_element(points_per_label.begin(), points_per_label.end(),
                       [](const auto& a, const auto& b) { return a.second < b.second; });
  return fill_largest(labels == most->first);
}

/// Slivers narrower than min_width_m cut (a); the water grown wall_offset_m into the band of wall
/// cells, so that the outline runs through the detections rather than along their inner edge
/// (b); notches narrower than 1 m closed (c).
cv::Mat settle_on_walls(cv::Mat water, const cv::Mat& walls, const Grid& grid,
                        const MarinaTraceConfig& config) {
  cv::morphologyEx(water, water, cv::MORPH_OPEN, disc(grid.cells(config.min_width_m)));
  water = fill_largest(water);  // (a)
  const cv::Mat step = cv::getStructuringElement(cv::MORPH_RECT, cv::Size(3, 3));
  cv::Mat grown;
  for (int i = 0; i < grid.cells(config.wall_offset_m); ++i) {
    cv::dilate(water, grown, step);
    water |= grown & walls;  // (b)
  }
  cv::morphologyEx(water, water, cv::MORPH_CLOSE, disc(grid.cells(1.0)));  // (c)
  return fill_largest(water);
}

}  // namespace

namespace {

/// Flips the cyclic runs of `value` shorter than min_length (unless one run is all there is).
void merge_short_runs(std::vector<bool>& flags, bool value, std::size_t min_length) {
  const std::size_t n = flags.size();
  std::size_t start = 0;
  while (start < n && flags[start] == flags[(start + n - 1) % n]) ++start;
  if (start == n) return;
  for (std::size_t i = start; i < start + n;) {
    std::size_t j = i;
    while (j < i + n && flags[j % n] == flags[i % n]) ++j;
    if (flags[i % n] == value && j - i < min_length) {
      for (std::size_t k = i; k < j; ++k) flags[k % n] = !value;
    }
    i = j;
  }
}

/// Per outline point: whether echo cells lie within wall_support_m; gaps in a wall and wall bits
/// inside an opening shorter than min_run_m merged into their surroundings.
std::vector<bool> on_wall(const std::vector<cv::Point>& outline, const cv::Mat& echoes,
                          const Grid& grid, const MarinaTraceConfig& config) {
  cv::Mat distance_cells;
  cv::distanceTransform(~echoes, distance_cells, cv::DIST_L2, cv::DIST_MASK_PRECISE);
  std::vector<bool> flags;
  for (const cv::Point& px : outline) {
    flags.push_back(distance_cells.at<float>(px) * grid.cell_m <= config.wall_support_m);
  }
  const auto min_cells = static_cast<std::size_t>(grid.cells(config.min_run_m));
  merge_short_runs(flags, false, min_cells);
  merge_short_runs(flags, true, min_cells);
  return flags;
}

/// Each run of wall (open) outline points simplified at simplify_wall_m (simplify_open_m),
/// keeping the points where the runs meet; counter-clockwise in the world frame.
BasinOutline simplified_outline(const std::vector<cv::Point>& outline,
                                const std::vector<bool>& flags, const Grid& grid,
                                const MarinaTraceConfig& config) {
  const std::size_t n = outline.size();
  std::size_t start = 0;
  while (start < n && flags[start] == flags[(start + n - 1) % n]) ++start;
  BasinOutline result;
  if (start == n) start = 0;
  for (std::size_t i = start; i < start + n;) {
    std::size_t j = i;
    while (j < i + n && flags[j % n] == flags[i % n]) ++j;
    std::vector<cv::Point> run;
    for (std::size_t k = i; k <= j; ++k) run.push_back(outline[k % n]);
    std::vector<cv::Point> kept;
    const double tolerance_m = flags[i % n] ? config.simplify_wall_m : config.simplify_open_m;
    cv::approxPolyDP(run, kept, tolerance_m / grid.cell_m, false);
    for (std::size_t k = 0; k + 1 < kept.size(); ++k) {
      result.ccw_polygon_m.push_back(grid.world(kept[k]));
      result.wall_edge.push_back(flags[i % n]);
    }
    i = j;
  }
  if (signed_double_area(result.ccw_polygon_m) < 0.0) {
    const std::size_t m = result.ccw_polygon_m.size();
    BasinOutline reversed;
    for (std::size_t k = 0; k < m; ++k) {
      reversed.ccw_polygon_m.push_back(result.ccw_polygon_m[m - 1 - k]);
      reversed.wall_edge.push_back(result.wall_edge[(2 * m - 2 - k) % m]);
    }
    return reversed;
  }
  return result;
}

/// The oriented box around the cells of one cluster, no side under min_size_m.
ClutterObject box_around(const std::vector<cv::Point>& cells, const Grid& grid, double min_size_m) {
  std::vector<cv::Point2f> centres;
  for (const cv::Point& px : cells)
    centres.emplace_back(static_cast<float>(px.x) + 0.5f, static_cast<float>(px.y) + 0.5f);
  const cv::RotatedRect box = cv::minAreaRect(centres);
  ClutterObject object;
  object.centre_m = grid.world(box.center - cv::Point2f(0.5f, 0.5f));
  object.length_m = std::max((box.size.width + 1.0) * grid.cell_m, min_size_m);
  object.width_m = std::max((box.size.height + 1.0) * grid.cell_m, min_size_m);
  object.yaw_rad = -box.angle * M_PI / 180.0;  // image rows point South
  return object;
}

/// Clusters of first detections (cells within wall_group_m joined) with a detection in the water
/// (or at its edge, beyond an opening) and at least clutter_wall_clearance_m from the outline's
/// walls: accepted when seen in clutter_min_revolutions.
void find_clutter(const std::vector<TraceBeam>& beams, const cv::Mat& hits, const cv::Mat& water,
                  const std::vector<cv::Point>& outline, const std::vector<bool>& on_wall,
                  const Grid& grid, const MarinaTraceConfig& config, MarinaTrace& trace) {
  cv::Mat off_wall(grid.size(), CV_8U, cv::Scalar(255));
  for (std::size_t i = 0; i < outline.size(); ++i) {
    if (on_wall[i]) off_wall.at<std::uint8_t>(outline[i]) = 0;
  }
  cv::Mat grouped, labels, wall_distance_cells;
  cv::distanceTransform(off_wall, wall_distance_cells, cv::DIST_L2, cv::DIST_MASK_PRECISE);
  cv::dilate(hits > 0, grouped, disc(grid.cells(config.wall_group_m)));
  const int count = cv::connectedComponents(grouped, labels, 8, CV_32S);
  std::vector<std::vector<cv::Point>> cells(count);
  std::vector<bool> near_wall(count, false), in_water(count, false);
  for (int r = 0; r < labels.rows; ++r) {
    for (int c = 0; c < labels.cols; ++c) {
      const int label = labels.at<int>(r, c);
      if (label == 0) continue;
      if (wall_distance_cells.at<float>(r, c) * grid.cell_m < config.clutter_wall_clearance_m) {
        near_wall[label] = true;
      }
      if (hits.at<int>(r, c) == 0) continue;
      cells[label].emplace_back(c, r);
      if (water.at<std::uint8_t>(r, c) != 0) in_water[label] = true;
    }
  }
  std::vector<std::set<int>> revolutions(count);
  std::vector<int> detections(count, 0);
  for (const TraceBeam& b : beams) {
    if (b.first_range_m <= 0.0) continue;
    const int label = labels.at<int>(grid.pixel(b.echo_world_m()));
    revolutions[label].insert(b.revolution);
    ++detections[label];
  }
  for (int label = 1; label < count; ++label) {
    if (near_wall[label] || !in_water[label]) continue;
    if (static_cast<int>(revolutions[label].size()) < config.clutter_min_revolutions) {
      ++trace.rejected_clusters;
      continue;
    }
    ClutterObject object = box_around(cells[label], grid, config.clutter_min_size_m);
    object.detections = detections[label];
    object.revolutions = static_cast<int>(revolutions[label].size());
    trace.clutter.push_back(object);
  }
}

}  // namespace

MarinaTrace trace_marina(const std::vector<TraceBeam>& beams,
                         const std::vector<Eigen::Vector2d>& track_m,
                         const MarinaTraceConfig& config) {
  if (beams.empty() || track_m.empty()) throw std::runtime_error("no beams or no track");
  const Grid grid = grid_around(beams, config.cell_m, config.max_range_m);
  const auto [hits, revolutions] = echo_counts(beams, grid);
  const cv::Mat echoes = echo_cells(hits, revolutions, config);
  const cv::Mat swept = swept_cells(beams, hits, grid, config);
  const cv::Mat water =
      settle_on_walls(flood_from_track(echoes, swept, track_m, grid, config.max_track_distance_m),
                      echoes, grid, config);
  const std::vector<cv::Point> outline = largest_outline(water);
  const std::vector<bool> outline_on_wall = on_wall(outline, echoes, grid, config);
  MarinaTrace trace;
  trace.outline = simplified_outline(outline, outline_on_wall, grid, config);
  if (const auto crossing = find_crossing_edges(trace.outline.ccw_polygon_m)) {
    throw std::runtime_error("the simplified outline crosses itself (edges " +
                             std::to_string(crossing->first) + " and " +
                             std::to_string(crossing->second) + ")");
  }
  find_clutter(beams, hits, water, outline, outline_on_wall, grid, config, trace);
  return trace;
}

}  // namespace msislab::sim
