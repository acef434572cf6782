#include "app/montecarlo_directory.hpp"

#include <cstdio>
#include <filesystem>

#include "io/atomic_file.hpp"
#include "io/input_error.hpp"
#include "io/text_lines.hpp"
#include "results/results.hpp"

namespace msislab::app {

namespace fs = std::filesystem;

std::string run_name(int run) {
  char name[32];
  std::snprintf(name, sizeof(name), "run_%04d", run);
  return name;
}

std::string run_dir(const std::string& dir, const std::string& method, int run) {
  return (fs::path(dir) / "runs" / method / run_name(run)).string();
}

std::vector<int> runs_of(const results::MonteCarloManifest& manifest) {
  std::vector<int> runs;
  for (int r = manifest.shard_index; r < manifest.runs; r += manifest.shard_count) {
    runs.push_back(r);
  }
  return runs;
}

std::string executable_digest(const std::string& executable_path) {
  const std::string bytes = io::read_whole_file(executable_path);
  std::uint64_t hash = 0xcbf29ce484222325ULL;  // FNV-1a offset basis
  for (const unsigned char byte : bytes) {
    hash ^= byte;
    hash *= 0x100000001b3ULL;  // FNV prime
  }
  char hex[17];
  std::snprintf(hex, sizeof hex, "%016llx", static_cast<unsigned long long>(hash));
  return hex;
}

void check_resumable(const std::string& dir, const results::MonteCarloManifest& manifest,
                     const DirectoryInputs& inputs, const std::string& scenario_path) {
  const fs::path d(dir);
  if (!fs::exists(d / "montecarlo.json")) return;
  const auto differs = [&](const char* name, bool present, const std::string& text) {
    const fs::path file = d / name;
    if (!fs::exists(file)) return present;
    return !present || io::read_whole_file(file.string()) != text;
  };
  if (differs("scenario.yaml", true, inputs.scenario_text)) {
    io::fail_file(dir, "holds runs of another scenario (its scenario.yaml differs from " +
                           scenario_path + "); choose another --out");
  }
  if (differs("config.yaml", manifest.has_config, inputs.config_text)) {
    io::fail_file(dir,
                  "holds runs made with another SLAM config (config.yaml); choose another --out");
  }
  if (differs("methods.yaml", manifest.has_methods_file, inputs.methods_text)) {
    io::fail_file(dir,
                  "holds runs made with another methods file (methods.yaml differs from "
                  "--methods-file, or one of them is absent); choose another --out");
  }
  const std::string& digest = manifest.executable_digest;
  const std::string made_by =
      results::read_manifest_json((d / "montecarlo.json").string()).executable_digest;
  if (made_by != digest) {
    io::fail_file(dir, "holds runs made by another msislab build (executable digest " +
                           (made_by.empty() ? std::string("not recorded") : made_by) +
                           ", this one " + digest +
                           "): its defaults or code may differ; choose another --out");
  }
}

void write_directory_header(const std::string& dir, const results::MonteCarloManifest& manifest,
                            const DirectoryInputs& inputs) {
  io::create_output_dir(dir);
  const fs::path d(dir);
  io::write_text_atomically((d / "scenario.yaml").string(), inputs.scenario_text);
  if (manifest.has_config)
    io::write_text_atomically((d / "config.yaml").string(), inputs.config_text);
  if (manifest.has_methods_file)
    io::write_text_atomically((d / "methods.yaml").string(), inputs.methods_text);
  results::write_manifest_json((d / "montecarlo.json").string(), manifest);
}

namespace {

MonteCarloRun read_run(const std::string& dir, const std::string& method, int run) {
  const fs::path rd(run_dir(dir, method, run));
  MonteCarloRun record;
  record.index = run;
  if (fs::exists(rd / "metrics.json")) {
    record.metrics = results::read_metrics_json((rd / "metrics.json").string()).metrics;
    if (fs::exists(rd / "errors.csv"))
      record.errors = results::read_errors_csv((rd / "errors.csv").string());
    if (fs::exists(rd / "nees.csv")) {
      for (const results::NeesSample& s : results::read_nees_csv((rd / "nees.csv").string())) {
        record.nees.push_back(s.nees);
      }
    }
  } else {
    record.failed = fs::exists(rd / "failed.json");
  }
  return record;
}

}  // namespace

std::vector<MethodSummary> write_summary_files(const std::string& dir,
                                               const results::MonteCarloManifest& manifest,
                                               const std::vector<int>& runs) {
  std::vector<MethodSummary> summaries;
  for (const std::string& method : manifest.methods) {
    std::vector<MonteCarloRun> records;
    for (const int r : runs) records.push_back(read_run(dir, method, r));
    summaries.push_back(summarise_runs(method, records));
  }
  for (std::size_t m = 1; m < summaries.size(); ++m) {
    summaries[m].paired = paired_difference(summaries[m], summaries.front());
  }
  const fs::path d(dir);
  results::write_summary_json((d / "summary.json").string(), summaries);
  results::write_montecarlo_nees_csv((d / "nees.csv").string(), summaries);
  results::write_error_spread_csv((d / "errors.csv").string(), summaries);
  results::write_error_histogram_csv((d / "error_histogram.csv").string(),
                                     error_histograms(summaries));
  results::write_seeds_csv((d / "seeds.csv").string(), runs, manifest.first_seed);
  return summaries;
}

std::size_t failed_runs(const std::string& dir, const std::vector<std::string>& methods,
                        const std::vector<int>& runs) {
  std::size_t failed = 0;
  for (const int r : runs) {
    bool any = false;
    for (const std::string& m : methods)
      any |= fs::exists(fs::path(run_dir(dir, m, r)) / "failed.json");
    failed += any;
  }
  return failed;
}

}  // namespace msislab::app
