// The SLAM configuration (--config SLAM.yaml): plain structs with defaults, parsed once by io/.
#pragma once

#include <vector>

#include "slam/beam_segmentation.hpp"
#include "slam/dead_reckoning.hpp"
#include "slam/evaluation.hpp"
#include "slam/trajectory_slam.hpp"

namespace msislab {

struct SlamConfig {
  DeadReckoningConfig dead_reckoning;
  SegmentationConfig segmentation;
  TrajectorySlamConfig trajectory_slam;
  std::vector<TimeSegment> segments;  ///< named windows scored separately in metrics.json
};

}  // namespace msislab
