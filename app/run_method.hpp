// One method run on a dataset read already (io/truth's RunInputs, from a directory or held in
// memory): dead reckoning, velocity integration or a trajectory SLAM on the sonar scans, timed and
// scored against the truth when there is one. `msislab run` writes what it returns; each Monte
// Carlo worker runs every method through it on the dataset it holds in memory.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "app/method_catalogue.hpp"
#include "dataset/sonar_readings.hpp"
#include "dataset/truth.hpp"
#include "eval/evaluation.hpp"
#include "results/results.hpp"
#include "slam/scan_sequence.hpp"
#include "slam/scan_slam_pipeline.hpp"

namespace msislab::app {

/// A method's results on a dataset, computed and not yet written.
struct MethodResult {
  std::string method;
  std::vector<StampedPose> trajectory;
  double depth_m = 0.0;                   ///< for the TUM z
  std::optional<RunMetrics> metrics;      ///< present when the dataset has truth
  std::vector<results::NeesSample> nees;  ///< per scan, with pose truth
  std::vector<ErrorSample> errors;        ///< position error at every truth stamp
  double t_first_truth_s = 0.0;
  std::optional<std::vector<PlacedScan>> scans;           ///< with sonar data
  std::optional<std::vector<results::MatchRow>> matches;  ///< SLAM methods
  /// A SLAM back end estimating calibration: its estimates after every scan (calibration.csv).
  std::vector<CalibrationSnapshot> calibration_history;
  /// The dataset's calibration with what the back end estimated added (calibration.yaml; the
  /// deviation and the clock offset): nullopt when it estimated none of those.
  std::optional<Calibration> estimated_calibration;
  /// A back end with an online estimate (the pose graph): the smoothed trajectory, written as
  /// trajectory_smoothed.tum and scored as metrics.json's smoothed_* diagnostics.
  std::optional<std::vector<StampedPose>> smoothed_trajectory;
};

/// What several methods on one dataset can share, filled by the first that needs it: the sonar
/// readings (read before any method's clock starts) and the scans placed by dead reckoning (which
/// dead reckoning itself places after its clock; every SLAM method still builds its own scans on
/// its clock).
struct SharedInputs {
  std::optional<dataset::SonarInput> sonar;
  std::optional<std::vector<PlacedScan>> dead_reckoning_scans;
};

/// The library pipeline's settings (slam/scan_slam_pipeline) from a dataset read already: its
/// start, the DVL and sonar mounts, the sonar's beams per revolution.
ScanSlamSetup scan_slam_setup(const dataset::RunInputs& in, const dataset::SonarInput& sonar);

struct ExternalSetup;  // app/external_method.hpp

/// Runs a method on a dataset read already (from a directory or held in memory), sharing with
/// the other methods on it through `shared` when given (the results are the same). An external
/// method (MethodKind::kExternal) runs its program as `external` says (required for it).
/// Throws io::InputError, or ExternalMethodError for an external method that gave no result.
MethodResult run_method(const Method& method, const dataset::RunInputs& in,
                        SharedInputs* shared = nullptr, const ExternalSetup* external = nullptr);

}  // namespace msislab::app
