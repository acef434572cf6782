// Tracing a harbour basin from the first sonar detections of a real run, projected into the world
// (docs/scenes.md, tools/make_stpere_marina.cpp): walls where the detections recur, water where
// the beams swept, openings left open where beams saw nothing, and the compact echo clusters
// inside the water (moored boats, pontoons, buoys) as clutter objects. Raster work with OpenCV.
#pragma once

#include <Eigen/Core>
#include <vector>

#include "sim/scene_builder.hpp"

namespace msislab::sim {

/// One sonar beam in the world frame.
struct TraceBeam {
  double t_s = 0.0;
  int revolution = 0;  ///< beams of one 360 deg sweep share it; increases with time
  Eigen::Vector2d head_world_m = Eigen::Vector2d::Zero();
  double bearing_world_rad = 0.0;
  double first_range_m = 0.0;  ///< the nearest detection; 0: nothing detected within range
  Eigen::Vector2d echo_world_m() const;
};

struct MarinaTraceConfig {
  double cell_m = 0.25;                ///< raster cell, m
  double max_range_m = 50.0;           ///< a beam with no detection swept this far, m
  int min_hits = 3;                    ///< first detections a 3x3-cell neighbourhood needs
  int min_revolutions = 3;             ///< ... from at least this many revolutions
  double wall_group_m = 1.0;           ///< detections this close belong to one cluster, m
  double short_of_echo_m = 1.0;        ///< a detected beam swept up to this short of its echo, m
  double max_track_distance_m = 50.0;  ///< water lies within this distance of the track, m
  double min_width_m = 1.5;            ///< water slivers narrower than this are cut, m
  double wall_offset_m = 1.0;          ///< the outline lies this far into the band of echoes, m
  double wall_support_m = 1.0;         ///< an outline this close to a wall runs on it, m
  double min_run_m = 3.0;              ///< wall or open stretches shorter than this are merged, m
  double simplify_wall_m = 0.3;        ///< Douglas-Peucker tolerance along walls, m
  double simplify_open_m = 2.0;        ///< ... along openings (the sweep's ragged limit), m
  int clutter_min_revolutions = 3;     ///< an echo cluster seen less often is noise, multipath
  double clutter_wall_clearance_m = 2.0;  ///< clusters closer to a wall belong to the wall, m
  double clutter_min_size_m = 0.5;        ///< smallest footprint side, m
};

/// A clutter object: the oriented box around an echo cluster.
struct ClutterObject {
  Eigen::Vector2d centre_m = Eigen::Vector2d::Zero();
  double length_m = 0.0;  ///< along yaw_rad
  double width_m = 0.0;
  double yaw_rad = 0.0;
  int detections = 0;   ///< first detections in the cluster
  int revolutions = 0;  ///< distinct revolutions that saw it
  std::vector<Eigen::Vector2d> ccw_footprint_m() const;
};

struct MarinaTrace {
  BasinOutline outline;                ///< the water's outline; walls only where echoes are
  std::vector<ClutterObject> clutter;  ///< accepted clusters
  int rejected_clusters = 0;           ///< clusters in the water seen in too few revolutions
};

/// Traces the basin from beams (time order) and the vehicle track. Throws std::runtime_error
/// when no water region holds the track or the outline is not a simple polygon.
MarinaTrace trace_marina(const std::vector<TraceBeam>& beams,
                         const std::vector<Eigen::Vector2d>& track_m,
                         const MarinaTraceConfig& config);

}  // namespace msislab::sim
