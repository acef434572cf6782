#include "app/montecarlo.hpp"

#include <filesystem>

#include "app/directory_lock.hpp"
#include "app/montecarlo_directory.hpp"
#include "io/input_error.hpp"
#include "io/text_lines.hpp"
#include "results/montecarlo_files.hpp"

namespace msislab::app {

namespace fs = std::filesystem;

namespace {

struct ShardHeader {
  results::MonteCarloManifest manifest;
  DirectoryInputs inputs;
};

ShardHeader read_shard(const std::string& shard) {
  const fs::path d(shard);
  if (!fs::exists(d / "montecarlo.json")) {
    io::fail_file(shard, "not a Monte Carlo directory (no montecarlo.json)");
  }
  ShardHeader header;
  header.manifest = results::read_manifest_json((d / "montecarlo.json").string());
  header.inputs.scenario_text = io::read_whole_file((d / "scenario.yaml").string());
  if (header.manifest.has_config) {
    header.inputs.config_text = io::read_whole_file((d / "config.yaml").string());
  }
  if (header.manifest.has_methods_file) {
    header.inputs.methods_text = io::read_whole_file((d / "methods.yaml").string());
  }
  return header;
}

void check_same_settings(const ShardHeader& a, const ShardHeader& b, const std::string& a_dir,
                         const std::string& b_dir) {
  const auto differ = [&](const std::string& what) {
    io::fail_file(b_dir, "made with another " + what + " than " + a_dir + "; cannot merge them");
  };
  if (a.inputs.scenario_text != b.inputs.scenario_text) differ("scenario (scenario.yaml)");
  if (a.manifest.has_config != b.manifest.has_config ||
      a.inputs.config_text != b.inputs.config_text) {
    differ("SLAM config (config.yaml)");
  }
  if (a.manifest.has_methods_file != b.manifest.has_methods_file ||
      a.inputs.methods_text != b.inputs.methods_text) {
    differ("methods file (methods.yaml)");
  }
  if (a.manifest.runs != b.manifest.runs) differ("--runs");
  if (a.manifest.methods != b.manifest.methods) differ("--methods");
  if (a.manifest.executable_digest != b.manifest.executable_digest) {
    differ("msislab build (executable_digest)");
  }
}

/// Replaces dst by a copy of src, copied aside first so dst is never half-copied.
void copy_run_dir(const fs::path& src, const fs::path& dst) {
  const fs::path tmp = dst.string() + ".tmp-merge";
  std::error_code ec;
  fs::remove_all(tmp, ec);
  fs::create_directories(dst.parent_path(), ec);
  fs::copy(src, tmp, fs::copy_options::recursive, ec);
  if (!ec) fs::remove_all(dst, ec);
  if (!ec) fs::rename(tmp, dst, ec);
  if (ec) io::fail_file(dst.string(), "cannot copy " + src.string() + " here: " + ec.message());
}

}  // namespace

MonteCarloOutcome merge_montecarlo(const MergeOptions& options) {
  if (options.shard_dirs.empty()) throw io::InputError("montecarlo merge: no SHARD_DIR given");
  std::vector<ShardHeader> shards;
  for (const std::string& dir : options.shard_dirs) {
    shards.push_back(read_shard(dir));
    check_same_settings(shards.front(), shards.back(), options.shard_dirs.front(), dir);
  }
  results::MonteCarloManifest manifest = shards.front().manifest;
  manifest.shard_index = 0;
  manifest.shard_count = 1;
  const ShardHeader& first = shards.front();
  const DirectoryLock lock(
      {options.out_dir, "montecarlo", "montecarlo merge", options.shard_dirs, false},
      "msislab montecarlo merge");
  check_resumable(options.out_dir, manifest, first.inputs,
                  (fs::path(options.shard_dirs.front()) / "scenario.yaml").string());
  write_directory_header(options.out_dir, manifest, first.inputs);

  // A run is taken from the first shard that finished it, else from one that recorded a failure.
  const std::vector<int> runs = runs_of(manifest);
  for (const std::string& method : manifest.methods) {
    for (const int r : runs) {
      const fs::path dst(run_dir(options.out_dir, method, r));
      bool copied = false;
      for (const std::string& shard : options.shard_dirs) {
        const fs::path src(run_dir(shard, method, r));
        std::error_code ec;
        if (!fs::is_directory(src) || fs::equivalent(src, dst, ec)) continue;
        const bool finished = fs::exists(src / "metrics.json");
        const bool failed = fs::exists(src / "failed.json");
        if (finished || (failed && !copied)) {
          copy_run_dir(src, dst);
          copied = true;
        }
        if (finished) break;
      }
    }
  }
  MonteCarloOutcome outcome;
  outcome.runs = runs.size();
  outcome.summary = write_summary_files(options.out_dir, manifest, runs);
  outcome.failed = failed_runs(options.out_dir, manifest.methods, runs);
  return outcome;
}

}  // namespace msislab::app
