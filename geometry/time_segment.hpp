// A named time window: the segments of a mission (the paper's loop, canal and exit) that a
// scenario declares and the scoring reports separately.
#pragma once

#include <string>

namespace msislab {

/// A named time window, in seconds from the first truth stamp: [begin_s, end_s).
struct TimeSegment {
  std::string name;
  double begin_s = 0.0;
  double end_s = 0.0;
};

}  // namespace msislab
