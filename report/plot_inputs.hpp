// What `msislab plot DIR` draws from, read and checked before anything is drawn: the result
// directories (DIR itself, or its subdirectories), their truth from the dataset each was run on,
// a Monte Carlo nees.csv, and one revolution of the dataset's raw sonar log.
#pragma once

#include <Eigen/Core>
#include <filesystem>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "dataset/sonar_revolution.hpp"
#include "dataset/truth.hpp"
#include "eval/evaluation.hpp"
#include "results/result_readers.hpp"
#include "results/results.hpp"
#include "results/sweep_files.hpp"

namespace msislab::report {

struct PlotOptions {
  std::string dir;
  std::string dataset_dir;  ///< replaces the dataset recorded in metrics.json; empty: as recorded
  int ellipse_every = 0;    ///< a 2-sigma ellipse at every k-th scan; 0: about 25 per figure
  int width_px = 1200;
  int height_px = 900;
  int revolution = -1;  ///< revolution of the acoustic image; -1: the middle one
};

/// One result directory of `msislab run`.
struct ResultData {
  std::string dir;
  std::string name;    ///< the folder's name
  std::string method;  ///< from metrics.json; the folder's name when there is none
  std::vector<StampedPose> trajectory;
  std::vector<StampedPose> scans;               ///< scans.csv; empty when absent
  std::vector<Eigen::Vector2d> map_points_m;    ///< map.ply; empty when absent
  std::shared_ptr<const dataset::Truth> truth;  ///< null when the dataset is unknown or has none
  std::vector<ErrorSample> errors;              ///< position errors against the truth
};

struct PlotInputs {
  PlotOptions options;
  /// DIR itself when it holds trajectory.tum; else its subdirectories that do (a comparison).
  std::vector<ResultData> results;
  bool comparison = false;
  std::vector<results::NeesRow> nees;                  ///< DIR/nees.csv of a Monte Carlo directory
  std::vector<results::ErrorSpreadRow> error_spread;   ///< its errors.csv, when present
  std::vector<ErrorHistogram> error_histograms;        ///< its error_histogram.csv, when present
  std::optional<results::SweepTable> sweep;            ///< DIR/sweep.csv of a sweep directory
  std::optional<dataset::SonarRevolution> revolution;  ///< when the dataset has a *_IS.log
};

/// Reads everything `plot` needs. Throws io::InputError for a missing DIR, a malformed file, a
/// recorded dataset that no longer exists, or a DIR with nothing to plot.
PlotInputs load_plot_inputs(const PlotOptions& options);

/// The result directories in a folder: its subdirectories holding a trajectory.tum, by name
/// (hidden folders and figures/ skipped).
std::vector<std::filesystem::path> result_subdirs(const std::filesystem::path& dir);

}  // namespace msislab::report
