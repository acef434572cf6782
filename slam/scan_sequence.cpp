#include "slam/scan_sequence.hpp"

#include <algorithm>

namespace msislab {

std::vector<PlacedScan> build_scans(const std::vector<BeamReadings>& beams,
                                    const NavigationLog& navigation,
                                    const DeadReckoningConfig& dead_reckoning,
                                    const Eigen::Vector2d& p_vehicle_dvl_m,
                                    const StampedPose& initial, const ScanBuilderConfig& config) {
  const auto first = std::find_if(beams.begin(), beams.end(),
                                  [&](const BeamReadings& b) { return b.t_s >= initial.t_s; });
  std::vector<double> times_s;
  for (auto it = first; it != beams.end(); ++it) times_s.push_back(it->t_s);
  // The scan centres are keys: their motions come from one clone each, exactly (composing the
  // per-beam increments as independent would be about 100 times overconfident: they share the
  // EKF's velocity error).
  const std::size_t per_scan = static_cast<std::size_t>(config.beams_per_scan);
  const std::vector<OdometrySample> odometry =
      odometry_at(navigation, dead_reckoning, p_vehicle_dvl_m, initial, times_s,
                  KeySamples{per_scan / 2, per_scan});

  ScanBuilder builder(config);
  std::vector<PlacedScan> scans;
  const std::size_t centre_offset = static_cast<std::size_t>(config.beams_per_scan) / 2;
  for (std::size_t i = 0; i < odometry.size(); ++i) {
    const BeamReadings& beam = *(first + static_cast<long>(i));
    if (auto scan = builder.add_beam(beam.t_s, odometry[i].motion, beam.readings)) {
      // The scan frame is the vehicle at the revolution's central beam.
      const std::size_t centre =
          i + 1 - static_cast<std::size_t>(config.beams_per_scan) + centre_offset;
      scan->motion = *odometry[centre].motion_since_key;
      scans.push_back({std::move(*scan), odometry[centre].pose});
    }
  }
  return scans;
}

}  // namespace msislab
