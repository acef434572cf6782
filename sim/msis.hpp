// The mechanically scanned imaging sonar: one beam at a time, at its own time and pose, rendered by
// ray casting into an echo intensity profile (docs/simulator.md gives the equations).
#pragma once

#include <cstdint>
#include <optional>
#include <random>
#include <vector>

#include "sim/scenario.hpp"
#include "sim/scene.hpp"
#include "sim/vehicle.hpp"

namespace msislab::sim {

/// When each beam is transmitted and where the head points: one step per beam, the transducer
/// angle index decreasing by one per step as in the St. Pere logs.
struct BeamSlot {
  std::uint64_t index = 0;  ///< beam number from the start
  double t_s = 0.0;
  double transducer_angle_rad = 0.0;
};
std::vector<BeamSlot> beam_schedule(const SonarConfig& sonar, double t_begin_s, double t_end_s);

/// What really happened on one beam, for truth/beams.csv.
struct BeamTruth {
  Pose2 vehicle;                            ///< true pose at transmit
  double bearing_vehicle_rad = 0.0;         ///< beam axis in the vehicle frame
  std::optional<double> first_hit_range_m;  ///< along the axis from the head; none in range
  std::optional<double> strongest_range_m;  ///< range of the strongest noise-free echo
  bool strongest_is_multipath = false;      ///< that echo came by a specular bounce
};

struct RenderedBeam {
  BeamSlot slot;
  std::vector<std::uint8_t> intensity;  ///< bins, bin j at (j + 1) x bin_m
  BeamTruth truth;
};

class MsisModel {
 public:
  MsisModel(const Scene& scene, const SonarConfig& sonar, double vehicle_depth_m);

  /// Renders one beam; rng supplies the speckle and noise of this beam only.
  RenderedBeam render(const BeamSlot& slot, const VehicleTrajectory& trajectory,
                      std::mt19937_64& rng) const;

  /// Number of rays cast per beam before bounces.
  std::size_t rays_per_beam() const { return rays_.size(); }

 private:
  struct RayTemplate {
    double azimuth_rad = 0.0;    ///< offset from the beam axis
    double elevation_rad = 0.0;  ///< above the axis
    double weight = 0.0;         ///< one-way transmit pattern, normalised over the beam
  };
  struct Echoes;
  struct Head;
  struct Ping;

  Head head_at(double t_s, const VehicleTrajectory& trajectory, double bearing_vehicle_rad) const;
  void trace_ray(const RayTemplate& ray, const Ping& ping, Echoes& echoes) const;
  void add_echo(const Ping& ping, const Eigen::Vector3f& first_hit_m, double path_m, double power,
                bool multipath, Echoes& echoes) const;
  BeamTruth truth_of(const Ping& ping, const Echoes& echoes, const Pose2& vehicle) const;
  std::vector<std::uint8_t> to_intensity(const Echoes& echoes, std::mt19937_64& rng) const;
  double tvg_db(double range_m) const;

  const Scene& scene_;
  SonarConfig sonar_;
  double depth_m_;
  std::vector<RayTemplate> rays_;
  double pattern_norm_ = 1.0;  ///< divides every one-way pattern value
};

/// Two-way transmission loss, linear power ratio: spherical spreading 1/r^4 and absorption
/// 2 alpha r dB (Urick). Falls strictly with range.
double two_way_loss(double range_m, double absorption_db_per_m);

}  // namespace msislab::sim
