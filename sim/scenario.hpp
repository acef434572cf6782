// A simulation scenario: plain structs with the St. Pere defaults in place, filled once from the
// scenario YAML by io/scenario_yaml (docs/simulator.md lists every key).
#pragma once

#include <Eigen/Core>
#include <cstdint>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "geometry/calibration.hpp"
#include "geometry/time_segment.hpp"
#include "sim/detection_model.hpp"
#include "sim/mesh.hpp"

namespace msislab::sim {

/// Materials by default are a harbour's (docs/scenes.md): concrete or stone walls, the calibrated
/// St. Pere values, and a mud floor 22 dB darker. The floor is found by geometry
/// (sim/scene_materials), so a mesh with a single group gets both.
struct SceneConfig {
  std::string mesh_path;  ///< resolved against the scenario file's folder
  /// Faces of groups without a material of their own that are not the bottom.
  Material default_material{"", 0.5f, 0.05f};
  /// Faces of groups without a material of their own that sim::bottom_faces finds to be the floor.
  Material bottom_material{"", 0.003f, 0.3f};
  std::map<std::string, Material> group_materials;  ///< by OBJ group name
  Material surface{"water_surface", 0.001f, 0.9f};  ///< the z = 0 plane
};

struct VehicleConfig {
  double depth_m = 1.5;
  double speed_mps = 0.2;
  std::vector<Eigen::Vector2d> path_m;  ///< waypoints in the scene frame, followed in order
  std::vector<double> leg_speeds_mps;   ///< optional, one per leg (path_m[i] to [i + 1]), m/s;
                                        ///< empty: every leg at speed_mps
  /// Optional heading history, (t_s from the start, yaw_deg in the scene frame) rows in time
  /// order: the vehicle points this way while it follows the path (crabbing, as the real St.
  /// Pere vehicle did); empty: along its course.
  std::vector<Eigen::Vector2d> heading_deg;
  double max_turn_rate_radps = 0.15;   ///< bound on |yaw rate|
  double lookahead_m = 3.0;            ///< pure-pursuit carrot distance along the path
  double start_time_s = 1093455407.0;  ///< log time of the first sample (Unix s)
  double step_s = 0.01;                ///< integration step of the truth
};

/// Shape of the transducer's one-way power pattern in each plane.
enum class BeamPattern {
  kGaussian,  ///< one-way exp(-(ln2 / 2) (2a/W)^2): no sidelobes
  kSinc,      ///< sinc^2 of a uniformly driven line aperture: nulls and -13 dB sidelobes
};

/// Which way the transducer angle of the logs steps from beam to beam.
enum class SonarRotation {
  kDecreasing,  ///< one step down per beam, as the St. Pere MiniKing's logs
  kIncreasing,  ///< one step up per beam
};

/// A sector scan: the head sweeps from first_index to last_index (transducer angle step indices,
/// 0..steps_per_revolution - 1) in the rotation's direction, then back, and so on, turning at
/// each end without repeating it (the Ping360's and the Tritech heads' sector modes).
struct SonarSector {
  int first_index = 0;
  int last_index = 0;
};

struct SonarConfig {
  int steps_per_revolution = 200;
  double revolution_s = 13.8;  ///< time of steps_per_revolution beams (a full turn's worth)
  SonarRotation rotation = SonarRotation::kDecreasing;
  std::optional<SonarSector> sector;  ///< none: whole turns
  /// The sonar logs beams until this time, s after the run's start (absent: the whole run), as
  /// the real St. Pere sonar log ends 3020 s into its GPS track.
  std::optional<double> stop_s;
  int bins = 500;
  double bin_m = 0.1;
  double horizontal_beamwidth_deg = 3.0;  ///< two-way -3 dB full width
  double vertical_beamwidth_deg = 35.0;   ///< two-way -3 dB full width
  double tilt_deg = 0.0;                  ///< beam axis below the horizontal, deg
  BeamPattern beam_pattern = BeamPattern::kGaussian;
  int rays_horizontal = 16;               ///< rays across the horizontal aperture
  int rays_vertical = 12;                 ///< rays across the vertical aperture
  double horizontal_span_beamwidths = 2;  ///< rays cover +-this many horizontal beamwidths
  double vertical_span_beamwidths = 1;    ///< rays cover +-this many vertical beamwidths
  /// Each ray stands for the patch of surface its cell of the aperture covers (its footprint):
  /// the echo scales with the patch's area and spreads over the patch's ranges. Off: a ray is a
  /// point scatterer whose echo lands in one bin.
  bool footprint = true;
  double pulse_length_us = 200.0;             ///< transmit pulse; an echo lasts c tau / 2 in range
  double receiver_time_constant_us = 1200.0;  ///< one-pole receiver filter: exponential tail
  double roughness_db = 10.0;                 ///< sd of the surfaces' backscatter variation, dB
  double roughness_length_m = 10.0;           ///< its correlation length along a surface
  /// The sound speed the sonar converts echo time to range with, m/s.
  double sound_speed_mps = 1500.0;
  /// The sound speed in the water, m/s (absent: sound_speed_mps). The sonar reports a surface at
  /// range r as r sound_speed_mps / water_sound_speed_mps: a range scale, which the dataset's
  /// calibration.yaml states (sonar.range_scale) unless stated_calibration hides it.
  std::optional<double> water_sound_speed_mps;
  double absorption_db_per_m = 0.0354;  ///< one-way, ~700 kHz in sea water (DAVE's value)
  double gain_db = 36.2;                ///< receiver gain added to the level
  double tvg_db_per_decade = 40.0;      ///< time-varying gain, dB per decade of range
  double noise_level_db = -140.0;       ///< background noise power before gain and TVG, dB
  double display_min_db = 0.0;          ///< level shown as intensity 0
  double display_max_db = 45.0;         ///< level shown as intensity 255
  bool speckle = true;                  ///< multiplicative Rayleigh (exponential power) speckle
  int speckle_looks = 1;                ///< independent looks averaged per bin (1: Rayleigh)
  int multipath_bounces = 1;            ///< specular bounces followed per ray
  double min_range_m = 0.3;             ///< returns closer than this are blanked (ring-down)
  SonarMount mount;                     ///< head position and bearing convention
};

struct DvlConfig {
  double rate_hz = 1.5;
  /// White noise per axis, m/s: the core of a contaminated normal. With probability
  /// outlier_probability a sample's noise (both axes) has outlier_sigma_mps instead. The
  /// defaults here and below are the St. Pere estimates (docs/simulator.md).
  double noise_sigma_mps = 0.104;
  double outlier_probability = 0.25;                   ///< chance of the wide noise per sample
  double outlier_sigma_mps = 0.37;                     ///< wide noise per axis, m/s
  Eigen::Vector2d bias_mps = Eigen::Vector2d::Zero();  ///< constant, DVL frame
  /// The DVL measures scale_factor times the true velocity (a transducer or sound speed error).
  double scale_factor = 1.0;
  /// Bottom lock is lost independently per sample with dropout_probability in the clear state and
  /// degraded_dropout_probability in the degraded state; the state switches as a Markov chain
  /// spending degraded_fraction of the time degraded, in periods of degraded_duration_s on
  /// average (degraded_fraction 0: always clear, independent dropouts).
  double dropout_probability = 0.0038;
  double degraded_dropout_probability = 0.07;
  double degraded_fraction = 0.2;
  double degraded_duration_s = 28.0;
  double max_altitude_m = 30.0;  ///< no bottom lock above this
  DvlMount mount;
};

struct MruConfig {
  double rate_hz = 10.0;
  double heading_noise_deg = 0.04;  ///< white noise, deg
  double bias_initial_deg = 0.0;
  double bias_random_walk_deg_per_sqrt_s = 0.01;  ///< heading bias random walk density
  /// One-cycle compass deviation (hard iron): the reading is off by
  /// cos_deg cos(yaw) + sin_deg sin(yaw), yaw in the scene frame.
  double deviation_cos_deg = 0.0;
  double deviation_sin_deg = 0.0;
  MruMount mount;
};

/// A GPS receiver on a buoy towed by the vehicle. The buoy stays put while the tether is slack and
/// is dragged toward the vehicle along the tether when it is taut; the fix is the buoy position
/// plus a first-order Gauss-Markov error and white noise. Defaults: the St. Pere estimates.
struct GpsConfig {
  bool enabled = true;
  double rate_hz = 1.0;
  double noise_sigma_m = 0.03;        ///< white noise per axis, m
  double correlated_sigma_m = 1.0;    ///< Gauss-Markov error per axis, stationary sd
  double correlation_time_s = 300.0;  ///< its correlation time, s
  /// Horizontal reach of the taut tether (a tether of length l at depth d reaches
  /// sqrt(l^2 - d^2)), m; 0 puts the buoy above the vehicle.
  double tether_length_m = 0.0;
  LocalFrame frame;  ///< geodetic origin of the scene frame
};

struct Scenario {
  std::string name = "scenario";
  std::uint64_t seed = 0;
  SceneConfig scene;
  VehicleConfig vehicle;
  SonarConfig sonar;
  DvlConfig dvl;
  MruConfig mru;
  GpsConfig gps;
  /// The detector that turns each simulated profile into *_detections.csv.gz, as the real
  /// dataset's were made (sim/detection_model).
  DetectionModelConfig detections;
  std::vector<TimeSegment> segments;
  /// What the dataset's calibration.yaml states, where it is not what the sensors do (the
  /// scenario's `stated_calibration`): an error left for the estimators to find. Absent: the
  /// file states the sensors' own mounts, deviation, clock offset and scale factors.
  std::optional<Calibration> stated_calibration;
  /// The scenario checks' warnings not to print (names of sim::kScenarioWarnings): what the
  /// author knows and means.
  std::vector<std::string> quiet_warnings;
};

/// The calibration the sensors of this scenario have (their mounts, deviation, clock offset, DVL
/// scale factor, sonar range scale and frame): what a perfect calibration would state.
Calibration true_calibration(const Scenario& scenario);

/// The calibration a dataset from this scenario carries: stated_calibration when the scenario
/// has one, else true_calibration.
Calibration calibration_of(const Scenario& scenario);

}  // namespace msislab::sim
