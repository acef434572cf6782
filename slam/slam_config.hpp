// The SLAM configuration (--config SLAM.yaml): plain structs with defaults, parsed once by io/.
#pragma once

#include <vector>

#include "geometry/time_segment.hpp"
#include "slam/beam_footprint.hpp"
#include "slam/beam_segmentation.hpp"
#include "slam/dead_reckoning.hpp"
#include "slam/pose_graph_slam.hpp"
#include "slam/trajectory_slam.hpp"

namespace msislab {

struct SlamConfig {
  DeadReckoningConfig dead_reckoning;
  SegmentationConfig segmentation;
  /// The beam's footprint: each scan's wall points moved back along their beams (off by default;
  /// slam/beam_footprint.hpp).
  FootprintConfig footprint;
  TrajectorySlamConfig trajectory_slam;  ///< the filters, and the front end of every SLAM method
  PoseGraphSlamConfig pose_graph;        ///< the pose-graph back end (method posegraph)
  std::vector<TimeSegment> segments;     ///< named windows scored separately in metrics.json
  /// A study's switch (trajectory_slam.linearisation_samples in the file): measure the filters'
  /// linearisation error epsilon with this many samples each (slam/linearisation_probe.hpp; in
  /// metrics.json). It does not change the estimate. 0: off.
  int linearisation_samples = 0;
  /// Take the dead reckoning's noise keys the config does not set from the dataset's own
  /// (a simulated dataset's navigation_noise.yaml: its scenario's sensors); false: the defaults.
  bool navigation_noise_from_dataset = false;
};

}  // namespace msislab
