#include "app/sweep_command.hpp"

#include <unistd.h>

#include <CLI/CLI.hpp>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <iomanip>
#include <iostream>
#include <memory>

#include "app/cli.hpp"
#include "app/directory_lock.hpp"
#include "app/method_catalogue.hpp"
#include "io/atomic_file.hpp"
#include "io/input_error.hpp"
#include "io/text_lines.hpp"
#include "results/montecarlo_files.hpp"
#include "settings/sweep_yaml.hpp"

namespace msislab::app {

namespace fs = std::filesystem;

namespace {

std::string cell_name(std::size_t cell) {
  char name[32];
  std::snprintf(name, sizeof name, "cell_%03zu", cell);
  return name;
}

/// The sweep file's copy in DIR: a DIR made from other bytes is refused before anything changes.
void check_same_sweep(const std::string& dir, const std::string& sweep_text,
                      const std::string& sweep_path) {
  const fs::path copy = fs::path(dir) / "sweep.yaml";
  if (fs::exists(copy) && io::read_whole_file(copy.string()) != sweep_text) {
    io::fail_file(dir, "holds the cells of another sweep (its sweep.yaml differs from " +
                           sweep_path + "); choose another --out");
  }
}

/// sweep.csv's rows from the cells' summary.json, in cell order then the summary's method order.
results::SweepTable sweep_table(const std::string& dir, const settings::Sweep& sweep) {
  results::SweepTable table;
  table.keys = sweep.keys;
  for (std::size_t c = 0; c < sweep.cells.size(); ++c) {
    const fs::path summary = fs::path(dir) / "cells" / cell_name(c) / "summary.json";
    if (!fs::exists(summary)) continue;
    std::vector<std::string> values;
    for (const std::string& key : sweep.keys) {
      std::string value;
      for (const auto& [k, v] : sweep.cells[c].overrides) {
        if (k == key) value = v.text;
      }
      values.push_back(value);
    }
    for (const results::StoredSummary& stored : results::read_summary_json(summary.string())) {
      const MethodSummary& s = stored.summary;
      results::SweepRow row;
      row.cell = static_cast<int>(c);
      row.values = values;
      row.method = s.method;
      row.runs = s.runs;
      row.failed = s.failed;
      row.mean_error_m = s.mean_error_m;
      if (s.mean_error_quantiles_m) {
        row.p05_m = (*s.mean_error_quantiles_m)[0];
        row.p50_m = (*s.mean_error_quantiles_m)[1];
        row.p95_m = (*s.mean_error_quantiles_m)[2];
      }
      row.anees = s.anees;
      row.nees_in_bounds_fraction = s.nees_in_bounds_fraction;
      if (s.paired) {
        row.paired_reference = s.paired->reference;
        row.paired_difference_m = s.paired->mean_m;
        row.paired_ci95_lower_m = s.paired->ci95_lower_m;
        row.paired_ci95_upper_m = s.paired->ci95_upper_m;
        row.paired_runs_lower = s.paired->runs_lower;
      }
      for (const auto& [name, value] : s.diagnostics) {
        if (name == "linearisation_observation") row.linearisation_observation = value;
        if (name == "linearisation_inversion") row.linearisation_inversion = value;
        if (name == "linearisation_pose") row.linearisation_pose = value;
      }
      table.rows.push_back(std::move(row));
    }
  }
  return table;
}

}  // namespace

SweepOutcome sweep(const SweepOptions& options, const MonteCarloLog& log) {
  int shard_index = 0, shard_count = 1;
  check_shard_and_jobs(options.shard, options.jobs, shard_index, shard_count);
  const settings::Sweep plan = settings::read_sweep(options.sweep_path);
  const MethodCatalogue catalogue = MethodCatalogue::with_methods_file(options.methods_file);
  for (const std::string& m : plan.methods) catalogue.at(m, options.sweep_path + ": key 'methods'");
  std::vector<settings::CellInputs> inputs;
  for (std::size_t c = 0; c < plan.cells.size(); ++c)
    inputs.push_back(settings::cell_inputs(plan, c));
  const std::string sweep_text = io::read_whole_file(options.sweep_path);

  const DirectoryLock lock(
      {options.out_dir, "sweep", "sweep", {options.sweep_path, options.methods_file}, false},
      "msislab sweep " + options.sweep_path);
  check_same_sweep(options.out_dir, sweep_text, options.sweep_path);
  io::write_text_atomically((fs::path(options.out_dir) / "sweep.yaml").string(), sweep_text);
  // Each cell keeps (and checks) its copy; this one gives the sweep's figures their titles.
  if (!options.methods_file.empty()) {
    io::write_text_atomically((fs::path(options.out_dir) / "methods.yaml").string(),
                              io::read_whole_file(options.methods_file));
  }

  SweepOutcome outcome;
  outcome.cells = plan.cells.size();
  for (std::size_t c = 0; c < plan.cells.size(); ++c) {
    const fs::path in_dir = fs::path(options.out_dir) / "inputs" / cell_name(c);
    io::create_output_dir(in_dir.string());
    io::write_text_atomically((in_dir / "scenario.yaml").string(), inputs[c].scenario_text);
    MonteCarloOptions mc;
    mc.scenario_path = (in_dir / "scenario.yaml").string();
    if (!inputs[c].config_text.empty()) {
      mc.config_path = (in_dir / "config.yaml").string();
      io::write_text_atomically(mc.config_path, inputs[c].config_text);
    }
    mc.runs = plan.runs;
    mc.methods = plan.methods;
    mc.methods_file = options.methods_file.empty() ? "" : io::absolute_path(options.methods_file);
    mc.jobs = options.jobs;
    mc.shard = options.shard;
    mc.out_dir = (fs::path(options.out_dir) / "cells" / cell_name(c)).string();
    log.log << "sweep: " << cell_name(c) << " (" << c + 1 << "/" << plan.cells.size()
            << "): " << settings::describe_cell(plan.cells[c]) << std::endl;
    const MonteCarloOutcome cell = montecarlo(mc, log);
    outcome.runs += cell.runs;
    outcome.executed += cell.executed;
    outcome.failed += cell.failed;
    if (cell.interrupted != 0) {
      outcome.interrupted = cell.interrupted;
      return outcome;
    }
  }
  outcome.table = sweep_table(options.out_dir, plan);
  results::write_sweep_csv((fs::path(options.out_dir) / "sweep.csv").string(), outcome.table);
  return outcome;
}

SweepOutcome merge_sweep(const std::string& out_dir, const std::vector<std::string>& shard_dirs) {
  if (shard_dirs.empty()) throw io::InputError("sweep merge: no SHARD_DIR given");
  std::string sweep_text;
  for (const std::string& shard : shard_dirs) {
    const fs::path copy = fs::path(shard) / "sweep.yaml";
    if (!fs::exists(copy)) io::fail_file(shard, "not a sweep directory (no sweep.yaml)");
    const std::string text = io::read_whole_file(copy.string());
    if (sweep_text.empty()) sweep_text = text;
    if (text != sweep_text) {
      io::fail_file(
          shard, "made from another sweep file than " + shard_dirs.front() + "; cannot merge them");
    }
  }
  const settings::Sweep plan =
      settings::read_sweep((fs::path(shard_dirs.front()) / "sweep.yaml").string());
  const DirectoryLock lock({out_dir, "sweep", "sweep merge", shard_dirs, false},
                           "msislab sweep merge");
  check_same_sweep(out_dir, sweep_text, shard_dirs.front() + "/sweep.yaml");
  io::write_text_atomically((fs::path(out_dir) / "sweep.yaml").string(), sweep_text);
  SweepOutcome outcome;
  outcome.cells = plan.cells.size();
  for (std::size_t c = 0; c < plan.cells.size(); ++c) {
    MergeOptions merge;
    merge.out_dir = (fs::path(out_dir) / "cells" / cell_name(c)).string();
    for (const std::string& shard : shard_dirs) {
      merge.shard_dirs.push_back((fs::path(shard) / "cells" / cell_name(c)).string());
    }
    const MonteCarloOutcome cell = merge_montecarlo(merge);
    outcome.runs += cell.runs;
    outcome.failed += cell.failed;
  }
  outcome.table = sweep_table(out_dir, plan);
  results::write_sweep_csv((fs::path(out_dir) / "sweep.csv").string(), outcome.table);
  return outcome;
}

namespace {

/// `sweep` or `sweep merge`'s options.
struct SweepCli {
  SweepOptions options;
  std::string merge_out;
  std::vector<std::string> merge_shards;
  bool no_plot = false;
  CLI::App* command = nullptr;
};

/// Runs `sweep` or `sweep merge`; the exit status (kRunsFailedStatus when a run of any cell has a
/// failed method, 128 + the signal when stopped).
int run_sweep_cli(const SweepCli& cli) {
  SweepOutcome outcome;
  std::string dir;
  if (cli.command->got_subcommand("merge")) {
    dir = cli.merge_out;
    outcome = merge_sweep(cli.merge_out, cli.merge_shards);
  } else {
    if (cli.options.sweep_path.empty()) throw io::InputError("sweep: SWEEP is required");
    if (cli.options.out_dir.empty()) throw io::InputError("sweep: --out is required");
    dir = cli.options.out_dir;
    outcome = sweep(cli.options, {std::cerr, isatty(STDERR_FILENO) == 1});
    if (outcome.interrupted != 0) {
      std::cerr << "sweep: stopped by " << sigabbrev_np(outcome.interrupted)
                << "; every worker ended, the finished runs are kept in " << dir
                << "; run the same command to resume" << std::endl;
      return 128 + outcome.interrupted;
    }
  }
  std::cout << "sweep: " << dir << " holds " << outcome.cells << " cells (" << outcome.executed
            << " runs done now, " << outcome.failed << " with a failed method); wrote sweep.csv"
            << std::endl;
  if (!cli.no_plot && cli.options.shard.empty()) draw_and_list_figures("sweep", dir);
  return failed_runs_status(
      cli.command->got_subcommand("merge") ? "sweep merge" : "sweep", outcome.failed, outcome.runs,
      (fs::path(dir) / "cells" / "*" / "runs" / "*" / "run_*" / "failed.json").string());
}

}  // namespace

void add_sweep_command(CLI::App& app, CommandLine& line) {
  auto cli = std::make_shared<SweepCli>();
  cli->command = app.add_subcommand(
      "sweep",
      "A Monte Carlo directory per cell of a grid (or list) of scenario and SLAM config overrides; "
      "resumable and shardable; writes sweep.csv and figures");
  cli->command->add_option("SWEEP", cli->options.sweep_path, "Sweep YAML (required unless merge)");
  cli->command->add_option("--out,-o", cli->options.out_dir,
                           "Sweep directory (required); an existing one is resumed");
  cli->command
      ->add_option("--jobs,-j", cli->options.jobs,
                   "Runs at once in each cell (default: one per hardware thread)")
      ->check(CLI::PositiveNumber);
  cli->command->add_option("--shard", cli->options.shard,
                           "i/N: in every cell only the runs r with r % N == i; merge afterwards");
  cli->command->add_option("--methods-file", cli->options.methods_file,
                           "Methods file (YAML) declaring external methods for the sweep file's "
                           "methods; passed to every cell's Monte Carlo (docs/formats.md)");
  cli->command->add_flag("--no-plot", cli->no_plot, "Do not draw the figures at the end");
  cli->command->require_subcommand(0, 1);
  CLI::App* m = cli->command->add_subcommand(
      "merge", "Merge sweep shard directories into OUT_DIR, cell by cell, and write sweep.csv");
  m->add_option("OUT_DIR", cli->merge_out, "Sweep directory to write")->required();
  m->add_option("SHARD_DIR", cli->merge_shards, "Shard directories made with --shard")->required();
  m->add_flag("--no-plot", cli->no_plot, "Do not draw the figures at the end");
  cli->command->callback([cli, &line] { line.exit_status = run_sweep_cli(*cli); });
}

}  // namespace msislab::app
