#include "app/run_command.hpp"

#include <CLI/CLI.hpp>
#include <filesystem>
#include <iomanip>
#include <iostream>
#include <memory>

#include "app/cli.hpp"
#include "app/eval_command.hpp"
#include "io/atomic_file.hpp"
#include "io/input_error.hpp"
#include "io/output_guard.hpp"
#include "io/results.hpp"
#include "report/methods.hpp"

namespace msislab::app {

namespace fs = std::filesystem;

void write_method_result(const std::string& out_dir, const MethodResult& result,
                         const std::string& dataset_label, bool write_map) {
  io::create_output_dir(out_dir);
  const fs::path out(out_dir);
  io::write_trajectory_tum((out / "trajectory.tum").string(), result.trajectory, result.depth_m);
  if (result.smoothed_trajectory) {
    io::write_trajectory_tum((out / "trajectory_smoothed.tum").string(),
                             *result.smoothed_trajectory, result.depth_m);
  }
  if (result.scans) {
    io::write_scans_csv((out / "scans.csv").string(), *result.scans);
    if (write_map) io::write_points_ply((out / "map.ply").string(), world_points(*result.scans));
  }
  if (result.matches) io::write_matches_csv((out / "matches.csv").string(), *result.matches);
  if (result.metrics) write_scores(out_dir, *result.metrics, result.nees, dataset_label);
}

RunOutcome run(const RunOptions& options) {
  report::method_info(options.method);  // an unknown method fails before anything is read
  const io::OutputRequest out{
      options.out_dir, "result", "run", {options.dataset_dir, options.config_path}, options.force};
  io::check_output_folder(out);
  const io::RunInputs in = io::load_run_inputs(options.dataset_dir, options.config_path);
  const MethodResult result = run_method(options.method, in);
  io::StagedFolder staged(out);
  write_method_result(staged.path(), result, io::absolute_path(options.dataset_dir));
  staged.commit();
  return {result.trajectory, result.metrics};
}

void add_run_command(CLI::App& app, CommandLine&) {
  auto options = std::make_shared<RunOptions>();
  CLI::App* run_cli = app.add_subcommand(
      "run",
      "Run a method on a dataset directory (real or synthetic) and write a result directory");
  run_cli
      ->add_option("DATASET_DIR", options->dataset_dir,
                   "Dataset directory (*_DVL.log, *_MTi.log, optional *_DGPS.log, "
                   "calibration.yaml, truth/)")
      ->required();
  run_cli->add_option("--method,-m", options->method, "Method: " + method_list())->required();
  run_cli
      ->add_option("--out,-o", options->out_dir,
                   "Result directory (trajectory.tum, metrics.json when truth exists)")
      ->required();
  run_cli->add_option("--config,-c", options->config_path,
                      "SLAM config YAML (defaults when absent; keys in docs/formats.md)");
  add_force_flag(*run_cli, options->force);
  run_cli->callback([options] {
    const RunOutcome outcome = run(*options);
    std::cout << "wrote " << options->out_dir << "/trajectory.tum (" << outcome.trajectory.size()
              << " poses)";
    if (outcome.metrics) {
      std::cout << std::fixed << std::setprecision(3) << "; mean error "
                << outcome.metrics->errors.mean_m << " m against " << outcome.metrics->truth
                << ", metrics.json";
    }
    std::cout << std::endl;
  });
}

}  // namespace msislab::app
