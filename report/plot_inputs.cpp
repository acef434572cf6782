#include "report/plot_inputs.hpp"

#include <algorithm>
#include <filesystem>
#include <map>

#include "dataset/dataset.hpp"
#include "io/input_error.hpp"
#include "io/output_guard.hpp"
#include "io/tum.hpp"

namespace msislab::report {

namespace fs = std::filesystem;

namespace {

bool is_result_dir(const fs::path& dir) { return fs::is_regular_file(dir / "trajectory.tum"); }

std::vector<StampedPose> read_trajectory(const std::string& path) {
  std::vector<StampedPose> trajectory;
  for (const io::TumPose& p : io::read_tum(path)) {
    trajectory.push_back({p.t_s, {Pose2(p.x_m, p.y_m, p.yaw_rad)}});
  }
  return trajectory;
}

/// Each dataset's truth is loaded once, however many results were run on it.
class Datasets {
 public:
  std::shared_ptr<const dataset::Truth> truth(const std::string& dir) {
    remember(dir);
    auto [it, inserted] = truths_.try_emplace(dir);
    if (inserted) {
      const dataset::DatasetFiles files = dataset::find_dataset_files(dir);
      dataset::Truth truth = dataset::load_truth(files, dataset::load_calibration(files));
      if (!truth.kind.empty())
        it->second = std::make_shared<const dataset::Truth>(std::move(truth));
    }
    return it->second;
  }
  void remember(const std::string& dir) {
    if (std::find(order_.begin(), order_.end(), dir) == order_.end()) order_.push_back(dir);
  }
  const std::vector<std::string>& in_order() const { return order_; }

 private:
  std::map<std::string, std::shared_ptr<const dataset::Truth>> truths_;
  std::vector<std::string> order_;
};

/// The dataset a result was run on: --dataset, else the one metrics.json records (empty: none).
std::string dataset_of(const fs::path& metrics_path, const std::string& recorded,
                       const PlotOptions& options) {
  if (!options.dataset_dir.empty()) return options.dataset_dir;
  if (recorded.empty()) return "";
  if (!fs::is_directory(recorded)) {
    io::fail_file(metrics_path.string(), "key 'dataset': '" + recorded +
                                             "' is not a directory (moved? pass --dataset DIR)");
  }
  return recorded;
}

ResultData load_result(const fs::path& dir, const PlotOptions& options, Datasets& datasets) {
  ResultData result;
  result.dir = dir.string();
  result.name = dir.filename().string();
  result.method = result.name;
  result.trajectory = read_trajectory((dir / "trajectory.tum").string());
  if (fs::is_regular_file(dir / "scans.csv")) {
    result.scans = results::read_scans_csv((dir / "scans.csv").string());
  }
  if (fs::is_regular_file(dir / "map.ply")) {
    result.map_points_m = results::read_points_ply((dir / "map.ply").string());
  }
  std::string recorded;
  const fs::path metrics = dir / "metrics.json";
  if (fs::is_regular_file(metrics)) {
    const results::StoredMetrics stored = results::read_metrics_json(metrics.string());
    result.method = stored.metrics.method;
    recorded = stored.dataset_dir;
  }
  const std::string dataset = dataset_of(metrics, recorded, options);
  if (!dataset.empty()) result.truth = datasets.truth(dataset);
  if (result.truth) result.errors = position_errors(result.trajectory, result.truth->positions);
  return result;
}

/// The revolution of the first dataset (--dataset first) that has a raw sonar log.
std::optional<dataset::SonarRevolution> find_revolution(const Datasets& datasets, int revolution) {
  for (const std::string& dir : datasets.in_order()) {
    if (dataset::find_dataset_files(dir).is_log) return dataset::read_revolution(dir, revolution);
  }
  if (revolution >= 0) {
    throw io::InputError("--revolution " + std::to_string(revolution) +
                         ": no dataset with a *_IS.log to draw it from");
  }
  return std::nullopt;
}

}  // namespace

std::vector<fs::path> result_subdirs(const fs::path& dir) {
  std::vector<fs::path> subdirs;
  // A dataset's truth/ holds a trajectory.tum too, but it is what the results are scored against.
  const bool dataset = io::output_kind(dir.string()) == "dataset" ||
                       dataset::find_dataset_files(dir.string()).dvl.has_value();
  for (const fs::directory_entry& entry : fs::directory_iterator(dir)) {
    const std::string name = entry.path().filename().string();
    if (dataset && name == "truth") continue;
    if (entry.is_directory() && name[0] != '.' && name != "figures" && is_result_dir(entry)) {
      subdirs.push_back(entry.path());
    }
  }
  std::sort(subdirs.begin(), subdirs.end());
  return subdirs;
}

PlotInputs load_plot_inputs(const PlotOptions& options) {
  const fs::path dir(options.dir);
  if (!fs::is_directory(dir)) io::fail_file(options.dir, "no such directory");
  PlotInputs in;
  in.options = options;
  Datasets datasets;
  if (!options.dataset_dir.empty()) datasets.remember(options.dataset_dir);
  if (fs::is_regular_file(dir / "sweep.csv")) {
    // A sweep directory: its cells are Monte Carlo directories; plot one by naming its folder.
    in.sweep = results::read_sweep_csv((dir / "sweep.csv").string());
    if (in.sweep->rows.empty()) io::fail_file((dir / "sweep.csv").string(), "no rows to plot");
    return in;
  }
  if (is_result_dir(dir)) {
    // A result directory (its own nees.csv is the per-scan NEES of that run).
    in.results.push_back(load_result(dir, options, datasets));
  } else if (fs::is_regular_file(dir / "nees.csv")) {
    // A Monte Carlo directory: its per-run results are many; plot one by naming its folder.
    in.nees = results::read_montecarlo_nees((dir / "nees.csv").string());
    if (fs::is_regular_file(dir / "errors.csv")) {
      in.error_spread = results::read_error_spread_csv((dir / "errors.csv").string());
    }
    if (fs::is_regular_file(dir / "error_histogram.csv")) {
      in.error_histograms =
          results::read_error_histogram_csv((dir / "error_histogram.csv").string());
    }
  } else {
    for (const fs::path& subdir : result_subdirs(dir)) {
      in.results.push_back(load_result(subdir, options, datasets));
    }
    in.comparison = !in.results.empty();
  }
  if (in.results.empty() && in.nees.empty()) {
    io::fail_file(options.dir,
                  "nothing to plot: no trajectory.tum or nees.csv here and no subdirectory with a "
                  "trajectory.tum");
  }
  in.revolution = find_revolution(datasets, options.revolution);
  return in;
}

}  // namespace msislab::report
