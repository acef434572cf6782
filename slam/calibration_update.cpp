#include "slam/calibration_update.hpp"

namespace msislab {

std::optional<Calibration> calibration_with_estimates(
    const Calibration& stated, const std::vector<CalibrationEstimate>& estimates) {
  Calibration c = stated;
  bool carried = false;
  for (const CalibrationEstimate& e : estimates) {
    // The states estimate what is left after the stated calibration: the two add.
    if (e.name == "compass_deviation_cos_deg") {
      c.mru.deviation_cos_deg += e.value;
    } else if (e.name == "compass_deviation_sin_deg") {
      c.mru.deviation_sin_deg += e.value;
    } else if (e.name == "clock_offset_s") {
      c.sonar.time_offset_s += e.value;
    } else if (e.name == "range_scale") {
      c.sonar.range_scale *= e.value;  // the states estimate the scale left: the two multiply
    } else if (e.name == "dvl_scale") {
      c.dvl.scale_factor *= e.value;
    } else {
      continue;
    }
    carried = true;
  }
  if (!carried) return std::nullopt;
  return c;
}

}  // namespace msislab
