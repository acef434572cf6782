#include "app/run_command.hpp"

#include <unistd.h>

#include <CLI/CLI.hpp>
#include <filesystem>
#include <iomanip>
#include <iostream>
#include <memory>

#include "app/cli.hpp"
#include "app/external_method.hpp"
#include "app/method_catalogue.hpp"
#include "app/method_result.hpp"
#include "app/run_method.hpp"
#include "io/atomic_file.hpp"
#include "io/input_error.hpp"
#include "io/output_guard.hpp"
#include "settings/external_config.hpp"

namespace msislab::app {

namespace fs = std::filesystem;

namespace {

/// A folder of msislab's beside the output for an external method's run, removed however the run
/// ends: the config it is given and its work folder ({out} and its stderr).
class ExternalWork {
 public:
  explicit ExternalWork(const std::string& out_dir) {
    const fs::path out = fs::absolute(fs::path(out_dir)).lexically_normal();
    const std::string name = out.has_filename() ? out.filename().string() : "result";
    // A name nothing else has: a folder that is there already (not msislab's) is never touched.
    const std::string stem = "." + name + ".external-" + std::to_string(::getpid());
    for (int i = 0;; ++i) {
      root_ = out.parent_path() / (stem + (i == 0 ? "" : "-" + std::to_string(i)));
      std::error_code ec;
      if (fs::create_directory(root_, ec)) break;
      if (ec || i == 1000) throw io::InputError(root_.string() + ": cannot make a work folder");
    }
  }
  ~ExternalWork() {
    std::error_code ec;
    fs::remove_all(root_, ec);
  }
  ExternalWork(const ExternalWork&) = delete;
  ExternalWork& operator=(const ExternalWork&) = delete;
  fs::path path(const char* name) const { return root_ / name; }

 private:
  fs::path root_;
};

MethodResult run_external(const Method& method, const RunOptions& options,
                          const dataset::RunInputs& in) {
  const ExternalWork work(options.out_dir);
  ExternalSetup setup;
  setup.dataset_dir = options.dataset_dir;
  // {config}: the --config given, or the dead reckoning the run resolved (without one, or with
  // the dataset's navigation noise taken in).
  setup.config_path = options.config_path;
  if (setup.config_path.empty()) {
    setup.config_path = work.path("config.yaml").string();
    settings::write_dead_reckoning_config(setup.config_path, in.config.dead_reckoning);
  } else if (in.config.navigation_noise_from_dataset) {
    setup.config_path = work.path("config.yaml").string();
    settings::write_resolved_config(setup.config_path, options.config_path,
                                    in.config.dead_reckoning);
  }
  setup.work_dir = work.path("run").string();
  return run_method(method, in, nullptr, &setup);
}

}  // namespace

RunOutcome run(const RunOptions& options) {
  const MethodCatalogue catalogue = MethodCatalogue::with_methods_file(options.methods_file);
  // An unknown method fails before anything is read.
  const Method& method = catalogue.at(options.method);
  const bool external = method.kind == MethodKind::kExternal;
  const io::OutputRequest out{
      options.out_dir,
      "result",
      "run",
      {options.dataset_dir, options.config_path, options.methods_file, options.calibration_path},
      options.force};
  io::check_output_folder(out);
  const dataset::RunInputs in =
      dataset::load_run_inputs(options.dataset_dir, options.config_path, options.calibration_path);
  if (!in.noise_note.empty()) std::cerr << "msislab: " << in.noise_note << '\n';
  const MethodResult result = external ? run_external(method, options, in) : run_method(method, in);
  io::StagedFolder staged(out);
  // An external method's scans carry no points: no map.
  write_method_result(staged.path(), result, io::absolute_path(options.dataset_dir), !external);
  staged.commit();
  return {result.trajectory, result.metrics};
}

void add_run_command(CLI::App& app, CommandLine& line) {
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
  run_cli->add_option(
      "--calibration", options->calibration_path,
      "calibration.yaml to read the dataset with instead of its own (e.g. the one a "
      "run estimating calibration wrote; docs/formats.md)");
  run_cli->add_option("--methods-file", options->methods_file,
                      "Methods file (YAML) declaring external methods, usable as --method "
                      "(docs/formats.md)");
  add_force_flag(*run_cli, options->force);
  run_cli->callback([options, &line] {
    RunOutcome outcome;
    try {
      outcome = run(*options);
    } catch (const ExternalMethodError& e) {
      std::cerr << "msislab: method '" << options->method << "' failed: " << e.what() << "\n";
      if (!e.stderr_tail().empty()) std::cerr << "its last stderr lines:\n";
      for (const std::string& l : e.stderr_tail()) std::cerr << "  " << l << "\n";
      std::cerr << std::flush;
      line.exit_status = 1;
      return;
    }
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
