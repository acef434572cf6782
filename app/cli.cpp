#include "app/cli.hpp"

#include <CLI/CLI.hpp>
#include <algorithm>
#include <filesystem>
#include <iostream>
#include <vector>

#include "app/montecarlo.hpp"
#include "report/methods.hpp"

namespace msislab::app {

void add_commands(CLI::App& app, CommandLine& line) {
  add_run_command(app, line);
  add_eval_command(app, line);
  add_simulate_command(app, line);
  add_montecarlo_command(app, line);
  add_sweep_command(app, line);
  add_image_command(app, line);
  add_scans_command(app, line);
  add_segment_command(app, line);
  add_plot_command(app, line);
  add_report_command(app, line);
  add_fidelity_command(app, line);
  add_check_command(app, line);
}

void add_force_flag(CLI::App& command, bool& force) {
  command.add_flag("--force", force,
                   "Replace the output folder even when msislab did not write it (its contents "
                   "are lost; an input of the command is never replaced)");
}

std::string method_list() {
  std::string methods;
  for (const std::string& m : report::method_names()) methods += (methods.empty() ? "" : ", ") + m;
  return methods;
}

int failed_runs_status(const std::string& command, std::size_t failed, std::size_t runs,
                       const std::string& failed_json) {
  if (failed == 0) return 0;
  std::cerr << command << ": finished, but " << failed << " of " << runs
            << " runs have a failed method (exit status " << kRunsFailedStatus << "); see "
            << failed_json << std::endl;
  return kRunsFailedStatus;
}

void draw_and_list_figures(const std::string& command, const std::string& dir) {
  const std::string failure = draw_montecarlo_figures(dir);
  if (!failure.empty()) {
    std::cerr << command << ": figures not drawn (" << failure << "); draw them with `msislab plot "
              << dir << "`" << std::endl;
    return;
  }
  std::vector<std::string> figures;
  for (const auto& entry : std::filesystem::directory_iterator(dir + "/figures")) {
    if (entry.path().extension() == ".png") figures.push_back(entry.path().filename().string());
  }
  std::sort(figures.begin(), figures.end());
  for (const std::string& name : figures) {
    std::cout << command << ": wrote " << dir << "/figures/" << name << "\n";
  }
  std::cout.flush();
}

}  // namespace msislab::app
