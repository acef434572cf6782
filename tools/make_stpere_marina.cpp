// msislab_make_stpere_marina: traces the St. Pere marina from the real sonar detections and writes
// it as a scene mesh (docs/scenes.md). Every beam is projected with the GPS position and MTi
// heading; sim::trace_marina turns them into the basin's outline (walls only where detections
// recur, openings left open) and clutter objects; sim::add_basin and sim::add_prism mesh them.
#include <CLI/CLI.hpp>
#include <Eigen/Core>
#include <algorithm>
#include <cmath>
#include <iomanip>
#include <iostream>
#include <map>
#include <opencv2/core.hpp>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>
#include <stdexcept>
#include <string>
#include <vector>

#include "dataset/dataset.hpp"
#include "eval/evaluation.hpp"
#include "geometry/calibration.hpp"
#include "geometry/se2.hpp"
#include "io/detections.hpp"
#include "io/mesh_io.hpp"
#include "io/stpere_logs.hpp"
#include "sim/marina_trace.hpp"
#include "sim/polygon_triangulation.hpp"
#include "sim/scenario_path.hpp"
#include "sim/scene_builder.hpp"
#include "slam/navigation.hpp"
#include "stats/sample_statistics.hpp"

namespace {

using msislab::Pose2;

struct Options {
  std::string dataset_dir;
  std::string out_path;
  std::string preview_path;
  double depth_m = 1.5;             ///< vehicle depth of the replica scenario (not logged), m
  double bottom_below_m = 1.9;      ///< bottom below the vehicle: the DVL's altitude, m
  double wall_top_m = 1.0;          ///< walls rise this far above the surface, m
  double wall_foot_offset_m = 0.0;  ///< a wall's foot lies this far into the water, m
  double clutter_top_m = 0.5;       ///< clutter objects rise from the bottom to this height, m
  double hull_draught_m = 1.0;      ///< ... or, where the real track crosses them, float this deep
  /// How far the detector's first bin lies before a wall at normal incidence (the centred window
  /// starts a run before its echo): the replica's, measured (docs/scenes.md, step 5), m.
  double detector_lead_m = 0.6;
  msislab::sim::MarinaTraceConfig trace;
};

/// The GPS fixes as a trajectory for interpolate_pose (positions only).
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

/// Every beam of the IS log inside the GPS time span, its nearest detection (if any) and its
/// transducer angle: from its detections, else one step (1.8 deg) less than the beam before.
std::vector<msislab::sim::TraceBeam> project_beams(const msislab::dataset::DatasetFiles& files,
                                                   const std::vector<msislab::PositionFix>& gps,
                                                   const msislab::NavigationLog& navigation,
                                                   const msislab::Calibration& calibration) {
  namespace io = msislab::io;
  std::map<std::int64_t, io::DetectionRecord> nearest;
  for (const io::DetectionRecord& d : io::read_detections(*files.detections)) {
    auto [it, inserted] = nearest.emplace(d.beam_row, d);
    if (!inserted && d.range_m < it->second.range_m) it->second = d;
  }
  const std::vector<io::BeamTimeRecord> times = io::read_beam_times_log(*files.beam_times);
  const std::vector<msislab::StampedPose> track = gps_track(gps);
  const double step_rad = 2.0 * M_PI / 200.0;
  std::vector<msislab::sim::TraceBeam> beams;
  double angle_rad = 0.0;
  int revolution = 0;
  for (std::size_t row = 0; row < times.size(); ++row) {
    const auto found = nearest.find(static_cast<std::int64_t>(row));
    angle_rad = found != nearest.end() ? found->second.angle_rad : angle_rad - step_rad;
    if (found != nearest.end()) revolution = found->second.keyframe;
    const double t_s = times[row].t_log_s + calibration.sonar.time_offset_s;  // navigation clock
    if (t_s < track.front().t_s || t_s > track.back().t_s) continue;
    const Eigen::Vector2d p_m = msislab::interpolate_pose(track, t_s).translation();
    const Pose2 T_world_vehicle(p_m.x(), p_m.y(),
                                msislab::nearest_heading(navigation.heading, t_s).yaw_rad);
    const msislab::SonarMount& mount = calibration.sonar;
    const Pose2 T_world_beam =
        T_world_vehicle +
        Pose2(mount.x_m, mount.y_m, msislab::sonar_bearing_in_vehicle(angle_rad, mount));
    beams.push_back({t_s, revolution, T_world_beam.translation(), T_world_beam.yaw(),
                     found != nearest.end() ? found->second.range_m : 0.0});
  }
  return beams;
}

/// Median DVL altitude (mean of the three beams' bottom ranges, bottom-locked rows) before and
/// after t_split_s from the first fix.
std::pair<double, double> median_altitudes_m(const std::string& dvl_path, double t0_s,
                                             double t_split_s) {
  std::vector<double> before, after;
  for (const msislab::io::DvlRecord& r : msislab::io::read_dvl_log(dvl_path)) {
    if (r.bottom_vel_status != 1.0) continue;
    const double altitude_m =
        (r.range_bottom_m[0] + r.range_bottom_m[1] + r.range_bottom_m[2]) / 3.0;
    (r.t_log_s - t0_s < t_split_s ? before : after).push_back(altitude_m);
  }
  const auto median_or_0 = [](std::vector<double> v) {
    return v.empty() ? 0.0 : msislab::median(std::move(v));
  };
  return {median_or_0(before), median_or_0(after)};
}

/// The mesh; clutter object i floats as a hull when floating[i] (the real track crosses it).
msislab::sim::TriangleMesh marina_mesh(const msislab::sim::MarinaTrace& trace,
                                       const std::vector<bool>& floating, const Options& options) {
  msislab::sim::MeshBuilder builder;
  const std::uint32_t walls = builder.group("walls", 0.6f, 0.3f);
  const std::uint32_t bottom = builder.group("bottom", 0.3f, 0.2f);
  msislab::sim::BasinProfile profile;
  profile.z_top_m = options.wall_top_m;
  profile.z_bottom_m = -(options.depth_m + options.bottom_below_m);
  profile.wall_foot_offset_m = options.wall_foot_offset_m;
  msislab::sim::add_basin(builder, trace.outline, profile, walls, bottom);
  if (!trace.clutter.empty()) {
    const std::uint32_t clutter = builder.group("clutter", 0.5f, 0.3f);
    for (std::size_t i = 0; i < trace.clutter.size(); ++i) {
      const double z_low_m = floating[i] ? -options.hull_draught_m : profile.z_bottom_m;
      msislab::sim::add_prism(builder, trace.clutter[i].ccw_footprint_m(), z_low_m,
                              options.clutter_top_m, clutter);
    }
  }
  return builder.mesh();
}

void write_preview(const std::string& path, const std::vector<msislab::sim::TraceBeam>& beams,
                   const std::vector<msislab::PositionFix>& gps,
                   const msislab::sim::MarinaTrace& trace) {
  constexpr double kPixelsPerM = 4.0;
  constexpr int kLegendPx = 60;  // band above the map for the legend
  const std::vector<Eigen::Vector2d>& polygon = trace.outline.ccw_polygon_m;
  Eigen::Vector2d lo = polygon.front(), hi = lo;
  for (const Eigen::Vector2d& p : polygon) lo = lo.cwiseMin(p), hi = hi.cwiseMax(p);
  lo -= Eigen::Vector2d(10.0, 10.0);
  hi += Eigen::Vector2d(10.0, 10.0);
  cv::Mat image(static_cast<int>((hi.y() - lo.y()) * kPixelsPerM) + kLegendPx,
                static_cast<int>((hi.x() - lo.x()) * kPixelsPerM), CV_8UC3,
                cv::Scalar(255, 255, 255));
  const auto to_image = [&](const Eigen::Vector2d& p_m) {
    return cv::Point(static_cast<int>((p_m.x() - lo.x()) * kPixelsPerM),
                     kLegendPx + static_cast<int>((hi.y() - p_m.y()) * kPixelsPerM));
  };
  for (const msislab::sim::TraceBeam& b : beams) {
    if (b.first_range_m > 0.0) {
      cv::circle(image, to_image(b.echo_world_m()), 0, cv::Scalar(110, 110, 110), cv::FILLED);
    }
  }
  std::vector<cv::Point> track_px;
  for (const msislab::PositionFix& fix : gps) track_px.push_back(to_image(fix.p_world_m));
  cv::polylines(image, track_px, false, cv::Scalar(200, 120, 0), 1, cv::LINE_AA);
  for (std::size_t i = 0; i < polygon.size(); ++i) {
    const bool wall = trace.outline.wall_edge[i];
    cv::line(image, to_image(polygon[i]), to_image(polygon[(i + 1) % polygon.size()]),
             wall ? cv::Scalar(0, 0, 220) : cv::Scalar(0, 150, 255), wall ? 2 : 1, cv::LINE_AA);
  }
  for (const msislab::sim::ClutterObject& object : trace.clutter) {
    std::vector<cv::Point> corners;
    for (const Eigen::Vector2d& q : object.ccw_footprint_m()) corners.push_back(to_image(q));
    cv::polylines(image, corners, true, cv::Scalar(0, 160, 0), 2, cv::LINE_AA);
  }
  const int bar_px = static_cast<int>(50.0 * kPixelsPerM);
  const cv::Point bar_start(20, image.rows - 20);
  cv::line(image, bar_start, bar_start + cv::Point(bar_px, 0), cv::Scalar(0, 0, 0), 3);
  const auto text = [&](const std::string& line, cv::Point at) {
    cv::putText(image, line, at, cv::FONT_HERSHEY_SIMPLEX, 0.6, cv::Scalar(0, 0, 0), 1,
                cv::LINE_AA);
  };
  text("50 m", bar_start + cv::Point(bar_px / 2 - 20, -10));
  text("North up. grey: first detections, blue: GPS track, red: walls,", cv::Point(10, 22));
  text("orange: open edge of the bottom (no wall seen), green: clutter", cv::Point(10, 46));
  if (!cv::imwrite(path, image)) throw std::runtime_error("cannot write " + path);
}

void print_summary(const msislab::sim::MarinaTrace& trace, const msislab::sim::TriangleMesh& mesh,
                   std::size_t beam_count, std::size_t echo_count) {
  const std::vector<Eigen::Vector2d>& polygon = trace.outline.ccw_polygon_m;
  Eigen::Vector2d lo = polygon.front(), hi = lo;
  for (const Eigen::Vector2d& p : polygon) lo = lo.cwiseMin(p), hi = hi.cwiseMax(p);
  const std::size_t n = polygon.size();
  const std::size_t wall_edges =
      std::count(trace.outline.wall_edge.begin(), trace.outline.wall_edge.end(), true);
  std::cout << std::fixed << std::setprecision(1) << "beams projected: " << beam_count << " ("
            << echo_count << " with a detection)\npolygon: " << n << " vertices (" << wall_edges
            << " wall edges), area " << 0.5 * msislab::sim::signed_double_area(polygon)
            << " m^2, bbox x [" << lo.x() << ", " << hi.x() << "] y [" << lo.y() << ", " << hi.y()
            << "] m\n";
  for (std::size_t i = 0; i < n; ++i) {  // each stretch of open edges, from its first vertex
    if (trace.outline.wall_edge[i] || !trace.outline.wall_edge[(i + n - 1) % n]) continue;
    std::size_t j = i;
    double length_m = 0.0;
    for (; !trace.outline.wall_edge[j % n] && j < i + n; ++j) {
      length_m += (polygon[(j + 1) % n] - polygon[j % n]).norm();
    }
    const Eigen::Vector2d& a = polygon[i];
    const Eigen::Vector2d& b = polygon[j % n];
    std::cout << "open (no wall seen): (" << a.x() << ", " << a.y() << ") to (" << b.x() << ", "
              << b.y() << "), " << length_m << " m along the outline\n";
  }
  std::cout << "clutter: " << trace.clutter.size() << " objects (" << trace.rejected_clusters
            << " clusters seen in too few revolutions rejected)\n";
  for (const msislab::sim::ClutterObject& o : trace.clutter) {
    std::cout << "  (" << o.centre_m.x() << ", " << o.centre_m.y() << ") " << o.length_m << " x "
              << o.width_m << " m, yaw " << o.yaw_rad * 180.0 / M_PI << " deg, " << o.detections
              << " detections in " << o.revolutions << " revolutions\n";
  }
  std::cout << "mesh: " << mesh.vertices_m.size() << " vertices, " << mesh.triangles.size()
            << " triangles\n";
}

void make_marina(const Options& options) {
  namespace dataset = msislab::dataset;
  namespace io = msislab::io;
  const dataset::DatasetFiles files = dataset::find_dataset_files(options.dataset_dir);
  if (!files.detections || !files.beam_times || !files.dvl) {
    throw std::runtime_error(options.dataset_dir +
                             ": needs *_detections.csv[.gz], *_IS_timestamps.log and *_DVL.log");
  }
  const msislab::Calibration calibration = dataset::load_calibration(files);
  const msislab::NavigationLog navigation = dataset::load_navigation(files, calibration);
  const std::vector<msislab::PositionFix> gps = dataset::load_gps_fixes(files, calibration);
  const std::vector<msislab::sim::TraceBeam> beams =
      project_beams(files, gps, navigation, calibration);
  if (beams.empty()) throw std::runtime_error("no beam inside the GPS time span");
  std::vector<Eigen::Vector2d> track_m;
  for (const msislab::PositionFix& fix : gps) track_m.push_back(fix.p_world_m);

  msislab::sim::MarinaTraceConfig trace_config = options.trace;
  trace_config.wall_offset_m += options.detector_lead_m;  // the walls behind the first detections
  const msislab::sim::MarinaTrace trace = msislab::sim::trace_marina(beams, track_m, trace_config);
  // An object the real vehicle went through is a moored hull it passed under (or one the GPS
  // misplaces): it floats, so the replica's vehicle passes under it too.
  std::vector<bool> floating;
  for (const msislab::sim::ClutterObject& o : trace.clutter) {
    floating.push_back(msislab::sim::path_enters(track_m, o.ccw_footprint_m()));
  }
  const msislab::sim::TriangleMesh mesh = marina_mesh(trace, floating, options);
  io::write_obj(options.out_path, mesh);
  if (!options.preview_path.empty()) write_preview(options.preview_path, beams, gps, trace);
  const std::size_t echoes = std::count_if(beams.begin(), beams.end(),
                                           [](const auto& b) { return b.first_range_m > 0.0; });
  print_summary(trace, mesh, beams.size(), echoes);
  for (std::size_t i = 0; i < trace.clutter.size(); ++i) {
    if (!floating[i]) continue;
    const msislab::sim::ClutterObject& o = trace.clutter[i];
    std::cout << "  the GPS track crosses (" << o.centre_m.x() << ", " << o.centre_m.y()
              << "): a hull from " << options.clutter_top_m << " m down to -"
              << options.hull_draught_m << " m\n";
  }
  constexpr double kShallowEndS = 2600.0;  // the DVL altitude drops from here on
  const auto [before_m, after_m] = median_altitudes_m(*files.dvl, gps.front().t_s, kShallowEndS);
  std::cout << std::setprecision(2) << "DVL altitude (median, bottom lock): " << before_m
            << " m before " << kShallowEndS << " s, " << after_m
            << " m after; bottom at z = " << -(options.depth_m + options.bottom_below_m)
            << " m\nwrote " << options.out_path << "\n";
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"Trace the St. Pere marina from the real sonar detections into a scene mesh (OBJ)"};
  Options options;
  app.add_option("--dataset", options.dataset_dir, "St. Pere dataset directory")->required();
  app.add_option("--out", options.out_path, "Output OBJ")->required();
  app.add_option("--preview", options.preview_path,
                 "Optional PNG: detections, track, outline, clutter");
  app.add_option("--depth", options.depth_m, "Vehicle depth, m")
      ->check(CLI::NonNegativeNumber)
      ->capture_default_str();
  app.add_option("--bottom-below", options.bottom_below_m,
                 "Bottom below the vehicle (the DVL's median altitude), m")
      ->check(CLI::PositiveNumber)
      ->capture_default_str();
  app.add_option("--hull-draught", options.hull_draught_m,
                 "A clutter object the GPS track crosses floats this deep, m")
      ->check(CLI::PositiveNumber)
      ->capture_default_str();
  app.add_option("--wall-foot-offset-m", options.wall_foot_offset_m,
                 "A wall's foot lies this far into the water from its top (0: vertical walls), m")
      ->check(CLI::NonNegativeNumber)
      ->capture_default_str();
  msislab::sim::MarinaTraceConfig& trace = options.trace;
  app.add_option("--cell", trace.cell_m, "Raster cell, m")
      ->check(CLI::Range(0.05, 2.0))
      ->capture_default_str();
  app.add_option("--min-revolutions", trace.min_revolutions,
                 "Revolutions whose detections a wall cell needs")
      ->check(CLI::PositiveNumber)
      ->capture_default_str();
  app.add_option("--simplify", trace.simplify_wall_m, "Outline tolerance along walls, m")
      ->check(CLI::PositiveNumber)
      ->capture_default_str();
  app.add_option("--clutter-min-revolutions", trace.clutter_min_revolutions,
                 "Revolutions that must see an echo cluster for it to be an object")
      ->check(CLI::PositiveNumber)
      ->capture_default_str();
  app.add_option("--wall-offset", trace.wall_offset_m,
                 "The outline lies this far into the band of first detections, m")
      ->check(CLI::NonNegativeNumber)
      ->capture_default_str();
  app.add_option("--detector-lead", options.detector_lead_m,
                 "... plus this much: how far the first detected bin lies before a wall, m")
      ->check(CLI::NonNegativeNumber)
      ->capture_default_str();
  app.add_option("--max-track-distance", trace.max_track_distance_m,
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
