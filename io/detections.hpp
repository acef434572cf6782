// The St. Pere derived sonar detections, *_detections.csv or *_detections.csv.gz (gzip), with the
// header "keyframe,beam_row,t_log_s,sensor_time_ms,angle_idx,angle_rad,range_m".
#pragma once

#include <cstdint>
#include <string>
#include <vector>

namespace msislab::io {

struct DetectionRecord {
  std::int32_t keyframe = 0;  ///< revolution index, 1-based
  std::int64_t beam_row = 0;  ///< 0-based row of the beam in *_IS_timestamps.log
  double t_log_s = 0.0;
  std::int64_t sensor_time_ms = 0;
  std::int32_t angle_idx = 0;  ///< transducer step, 0..199
  double angle_rad = 0.0;      ///< transducer angle
  double range_m = 0.0;        ///< range of the detected bin
  bool operator==(const DetectionRecord&) const;
};

/// Reads .csv or .csv.gz (chosen by the file name). Rows must be in non-decreasing beam_row order.
std::vector<DetectionRecord> read_detections(const std::string& path);
/// Writes .csv or .csv.gz (chosen by the file name), atomically.
void write_detections(const std::string& path, const std::vector<DetectionRecord>& rows);

}  // namespace msislab::io
