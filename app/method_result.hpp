// Scoring a method's result against the truth and writing its result directory (docs/formats.md):
// the one unit that `run`, `eval`, `montecarlo` and an external method's run all call.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "app/run_method.hpp"
#include "dataset/truth.hpp"
#include "eval/evaluation.hpp"
#include "results/results.hpp"

namespace msislab::app {

/// Position errors of a trajectory against the truth, their statistics and the segment means
/// (windows in seconds from the first truth stamp). InputError naming `source` when no truth stamp
/// falls inside the trajectory's span.
RunMetrics score_trajectory(const dataset::Truth& truth, const std::vector<StampedPose>& trajectory,
                            const std::vector<TimeSegment>& segments, const std::string& source);
/// The same from the position errors (position_errors) computed already.
RunMetrics score_errors(const dataset::Truth& truth, const std::vector<ErrorSample>& errors,
                        const std::vector<TimeSegment>& segments, const std::string& source);

/// The NEES of each scan pose against the pose truth; empty when the truth has no poses (GPS).
std::vector<results::NeesSample> scan_nees(const std::vector<StampedPose>& scan_poses,
                                           const dataset::Truth& truth);

/// The average NEES (ANEES) of the samples; nullopt when there are none.
std::optional<double> average_nees(const std::vector<results::NeesSample>& nees);

/// Writes metrics.json and nees.csv into a result directory; a stale nees.csv is removed when
/// there are no NEES samples.
void write_scores(const std::string& out_dir, const RunMetrics& metrics,
                  const std::vector<results::NeesSample>& nees, const std::string& dataset_dir,
                  const std::string& truth_file = "");

/// Writes the files of a result directory (docs/formats.md) into the new folder out_dir:
/// trajectory.tum, trajectory_smoothed.tum, scans.csv, map.ply (with write_map), matches.csv,
/// metrics.json and nees.csv, as far as the result has them. dataset_label is recorded in
/// metrics.json as the dataset.
void write_method_result(const std::string& out_dir, const MethodResult& result,
                         const std::string& dataset_label, bool write_map = true);

}  // namespace msislab::app
