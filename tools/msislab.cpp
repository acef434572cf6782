// The msislab command line: parses arguments and calls the app/ commands. Exit status 0 on success,
// 2 on bad input with one line on stderr naming the file, line or key (docs/cli.md).
#include <CLI/CLI.hpp>

#include <iomanip>
#include <iostream>

#include "app/run_command.hpp"
#include "io/input_error.hpp"

namespace {

constexpr int kBadInput = 2;

void add_run_command(CLI::App& app, msislab::app::RunOptions& options) {
  CLI::App* run = app.add_subcommand(
      "run",
      "Run a method on a dataset directory (real or synthetic) and write a result directory");
  run->add_option("DATASET_DIR", options.dataset_dir,
                  "Dataset directory (*_DVL.log, *_MTi.log, optional *_DGPS.log, calibration.yaml, "
                  "truth/)")
      ->required();
  std::string methods;
  for (const std::string& m : msislab::app::available_methods()) {
    methods += (methods.empty() ? "" : ", ") + m;
  }
  run->add_option("--method,-m", options.method, "Method: " + methods)->required();
  run->add_option("--out,-o", options.out_dir,
                  "Result directory (trajectory.tum, metrics.json when truth exists)")
      ->required();
  run->add_option("--config,-c", options.config_path,
                  "SLAM config YAML (defaults when absent; keys in docs/formats.md)");
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"msislab: a testbed for underwater SLAM with a mechanically scanned imaging sonar"};
  app.require_subcommand(1);
  app.set_version_flag("--version", "msislab 0.1.0");
  msislab::app::RunOptions run_options;
  add_run_command(app, run_options);

  try {
    app.parse(argc, argv);
  } catch (const CLI::Success& e) {
    return app.exit(e);
  } catch (const CLI::ParseError& e) {
    std::cerr << "msislab: " << e.what() << " (see msislab --help)\n";
    return kBadInput;
  }

  try {
    if (app.got_subcommand("run")) {
      const msislab::app::RunOutcome outcome = msislab::app::run(run_options);
      std::cout << "wrote " << run_options.out_dir << "/trajectory.tum ("
                << outcome.trajectory.size() << " poses)";
      if (outcome.metrics) {
        std::cout << std::fixed << std::setprecision(3) << "; mean error "
                  << outcome.metrics->errors.mean_m << " m against " << outcome.metrics->truth
                  << ", metrics.json";
      }
      std::cout << std::endl;
    }
  } catch (const msislab::io::InputError& e) {
    std::cerr << "msislab: " << e.what() << "\n";
    return kBadInput;
  }
  return 0;
}
