// The mechanically scanned imaging sonar: one beam at a time, at its own time and pose, rendered by
// ray casting into an echo intensity profile (docs/simulator.md gives the equations).
#pragma once

#include <cstdint>
#include <optional>
#include <random>
#include <string>
#include <vector>

#include "sim/msis_beam.hpp"
#include "sim/msis_receiver.hpp"
#include "sim/random.hpp"
#include "sim/scenario.hpp"
#include "sim/scene.hpp"
#include "sim/vehicle.hpp"

namespace msislab::sim {

/// When each beam is transmitted and where the head points: one step per beam every
/// revolution_s / steps_per_revolution, the transducer angle index stepping by one in the
/// rotation's direction from 0 (whole turns), or back and forth over the sector from its first
/// index.
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
  std::string strongest_surface;  ///< material (group) name of the surface that returned it
  /// The horizontal angle from the transmit axis to that echo's first surface, seen from the
  /// head, counter-clockwise from above (rad): how far off the axis the reading's source lies.
  std::optional<double> strongest_bearing_offset_rad;
};

struct RenderedBeam {
  BeamSlot slot;
  std::vector<std::uint8_t> intensity;  ///< bins, bin j at (j + 1) x bin_m
  std::uint32_t rays_cast = 0;          ///< primary and bounce rays traced for this beam
  BeamTruth truth;
};

/// What the sonar receives on one beam before speckle and noise: no random draw goes into it, so
/// it is the same for every seed of a scenario.
struct BeamEchoes {
  BeamSlot slot;
  BeamTruth truth;
  std::uint32_t rays_cast = 0;  ///< primary and bounce rays traced for this beam
  std::uint32_t first_bin = 0;  ///< power[k] is bin first_bin + k; the bins around it hold none
  std::vector<double> power;    ///< direct and specular echo power per bin
};

class MsisModel {
 public:
  MsisModel(const Scene& scene, const SonarConfig& sonar, double vehicle_depth_m);

  /// Renders one beam; rng supplies the speckle and noise of this beam only. The same as
  /// receive(trace(slot, trajectory), rng).
  RenderedBeam render(const BeamSlot& slot, const VehicleTrajectory& trajectory, Rng& rng) const;
  /// A beam's rays traced and their echoes gathered over the bins, with the beam's truth.
  BeamEchoes trace(const BeamSlot& slot, const VehicleTrajectory& trajectory) const;
  /// The beam as displayed: speckle, the pulse's spread, noise, gain, TVG and quantisation.
  RenderedBeam receive(const BeamEchoes& echoes, Rng& rng) const;

  /// The receiver of this sonar (what receive() uses), without a scene.
  static MsisReceiver receiver_of(const SonarConfig& sonar);

  /// Number of rays cast per beam before bounces.
  std::size_t rays_per_beam() const { return rays_.size(); }

  /// The primary rays of a beam (what render() casts first), for benchmarks and checks.
  std::vector<Ray> primary_rays(const BeamSlot& slot, const VehicleTrajectory& trajectory) const;

 private:
  struct RayTemplate {
    double azimuth_rad = 0.0;    ///< offset from the beam axis
    double elevation_rad = 0.0;  ///< above the axis
    double weight = 0.0;         ///< one-way transmit pattern, normalised over the beam
    Eigen::Vector3f direction_beam = Eigen::Vector3f::UnitX();  ///< axis along x, tilt applied
    /// The ray's cell of the aperture: d direction / d azimuth x cell width, and likewise in
    /// elevation (beam frame).
    Eigen::Vector3f cell_azimuth_beam = Eigen::Vector3f::Zero();
    Eigen::Vector3f cell_elevation_beam = Eigen::Vector3f::Zero();
    double cell_sr = 0.0;  ///< solid angle of the cell, sr
  };
  /// The rays across the aperture with their one-way pattern, not yet normalised.
  static std::vector<RayTemplate> aperture_rays(const SonarConfig& sonar);
  /// A ray's route through the scene while it is followed, bounce by bounce.
  struct Route;
  /// Working memory of one beam, kept per thread across beams.
  struct Workspace;

  SonarHead head_at(double t_s, const VehicleTrajectory& trajectory,
                    double bearing_vehicle_rad) const;
  Ping ping_of(const BeamSlot& slot, const VehicleTrajectory& trajectory) const;
  void primary_rays(const Ping& ping, std::vector<Ray>& rays) const;
  /// Follows every primary ray that hit, all routes a bounce at a time (each bounce's rays
  /// traced together), each surface's echo into the profile; returns the rays cast after the
  /// primary ones.
  std::uint32_t trace_routes(const Ping& ping, Workspace& work) const;
  /// The echo of the surface a route has reached at `hit_point_m`, along direction `d`.
  Echo echo_at(const Route& route, const Eigen::Vector3f& d, const Eigen::Vector3f& hit_point_m,
               const RayHit& hit, int bounce) const;
  /// Range extent (m) of the footprint of a ray's cell on the surface it hits; 0 when the
  /// footprint spread is off.
  double footprint_extent(double path_m, const Eigen::Vector3f& direction,
                          const Eigen::Vector3f& cell_azimuth,
                          const Eigen::Vector3f& cell_elevation,
                          const Eigen::Vector3f& normal) const;
  /// Area (m^2) of the footprint of a ray's cell on a surface; 1 when footprints are off (a ray
  /// is then a point scatterer).
  double footprint_area(double path_m, double cell_sr, double cos_incidence) const;
  /// ln of the surface's backscatter factor at a point (roughness; the factor has mean 1).
  double roughness_log_gain(const Eigen::Vector3f& point_m) const;
  BeamTruth truth_of(const Ping& ping, const EchoProfile& profile, const Pose2& vehicle) const;

  const Scene& scene_;
  SonarConfig sonar_;
  double depth_m_;
  std::vector<RayTemplate> rays_;
  double pattern_norm_ = 1.0;  ///< divides every one-way pattern value
  MsisReceiver receiver_;
};

/// A traced beam as displayed through `receiver` (MsisModel::receive without the model).
RenderedBeam receive_beam(const MsisReceiver& receiver, const BeamEchoes& echoes, Rng& rng);

}  // namespace msislab::sim
