// The folders the results page is built from, read back: result folders (their metrics.json and
// figures), Monte Carlo directories (summary.json, montecarlo.json and figures).
#include <algorithm>
#include <filesystem>

#include "dataset/dataset.hpp"
#include "io/input_error.hpp"
#include "report/method_styles.hpp"
#include "report/plot_inputs.hpp"
#include "report/results_page.hpp"

namespace msislab::report {

namespace fs = std::filesystem;

namespace {
/// PNG files of DIR/figures, sorted; InputError when the folder is missing or holds none, or when
/// a figure is older than one of `data` (the files it was drawn from, written again since: a
/// Monte Carlo resumed with another method, a result scored again).
std::vector<std::string> figures_of(const std::string& dir, const std::vector<fs::path>& data) {
  const fs::path folder = fs::path(dir) / "figures";
  std::vector<std::string> names;
  std::error_code ec;
  for (const auto& entry : fs::directory_iterator(folder, ec)) {
    if (entry.is_regular_file() && entry.path().extension() == ".png") {
      names.push_back(entry.path().filename().string());
    }
  }
  if (names.empty()) {
    io::fail_file(folder.string(), "no figures (draw them first: msislab plot " + dir + ")");
  }
  std::sort(names.begin(), names.end());
  for (const std::string& name : names) {
    const fs::file_time_type drawn = fs::last_write_time(folder / name);
    for (const fs::path& file : data) {
      if (fs::last_write_time(file) > drawn) {
        io::fail_file((folder / name).string(),
                      "was drawn before " + file.string() +
                          " was written (draw the figures again: msislab plot " + dir + ")");
      }
    }
  }
  return names;
}

/// A dataset's name: the prefix of its *_DVL.log ("stpere_replica", "_040825_1735"), else the name
/// of its folder; empty when no dataset is recorded.
std::string dataset_name(const std::string& dataset_dir) {
  if (dataset_dir.empty()) return "";
  if (fs::is_directory(dataset_dir)) {
    const dataset::DatasetFiles files = dataset::find_dataset_files(dataset_dir);
    if (files.dvl) {
      const std::string log = fs::path(*files.dvl).filename().string();
      return log.substr(0, log.size() - std::string("_DVL.log").size());
    }
  }
  return fs::path(dataset_dir).lexically_normal().filename().string();
}

}  // namespace

ResultFolder read_result_folder(const MethodStyles& styles, const std::string& dir,
                                const std::string& label) {
  if (!fs::is_directory(dir)) io::fail_file(dir, "not a directory");
  ResultFolder folder;
  folder.label = label;
  folder.dir = dir;
  std::vector<fs::path> data;
  for (const fs::path& sub : result_subdirs(dir)) {
    if (!fs::is_regular_file(sub / "metrics.json")) continue;  // run without truth: no scores
    data.push_back(sub / "metrics.json");
    const results::StoredMetrics stored =
        results::read_metrics_json((sub / "metrics.json").string());
    if (folder.dataset.empty()) folder.dataset = stored.dataset_dir;
    folder.results.push_back(stored.metrics);
  }
  if (folder.results.empty()) {
    io::fail_file(dir, "no result directories (subdirectories with a metrics.json)");
  }
  std::stable_sort(folder.results.begin(), folder.results.end(),
                   [&](const RunMetrics& a, const RunMetrics& b) {
                     return styles.rank(a.method) < styles.rank(b.method);
                   });
  folder.figures = figures_of(dir, data);
  folder.scenario = dataset_name(folder.dataset);
  return folder;
}

MonteCarloFolder read_montecarlo_folder(const std::string& dir) {
  if (!fs::is_directory(dir)) io::fail_file(dir, "not a directory");
  MonteCarloFolder mc;
  mc.label = "montecarlo";
  mc.dir = dir;
  mc.manifest = results::read_manifest_json((fs::path(dir) / "montecarlo.json").string());
  const fs::path summary = fs::path(dir) / "summary.json";
  if (!fs::is_regular_file(summary)) {
    io::fail_file(summary.string(), "missing (the Monte Carlo has not finished or been merged)");
  }
  mc.methods = results::read_summary_json(summary.string());
  mc.figures = figures_of(dir, {summary});
  return mc;
}

}  // namespace msislab::report
