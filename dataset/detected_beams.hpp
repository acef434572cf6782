// The beams of a detections file, grouped and checked for what the sonar statistics
// (eval/sonar_statistics.hpp) rely on.
#pragma once

#include <cstddef>
#include <string>
#include <vector>

#include "eval/sonar_statistics.hpp"
#include "io/detections.hpp"

namespace msislab::dataset {

/// The beams of the detections file `path` that have rows, in beam_row order. Checks what the
/// statistics rely on, with io::InputError naming the file and the row: every beam_row is a row of
/// the beam times (beam_count of them), a beam's rows share keyframe and angle, the keyframe never
/// decreases, a keyframe spans at most beams_per_revolution beam rows, the keyframes from the first
/// to the last hold no more beams than the beam times, and every range lies in [0, max_range_m].
std::vector<DetectedBeam> group_detections(const std::vector<io::DetectionRecord>& rows,
                                           const std::string& path, std::size_t beam_count,
                                           int beams_per_revolution, double max_range_m);

}  // namespace msislab::dataset
