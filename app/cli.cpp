#include "app/cli.hpp"

#include <CLI/CLI.hpp>
#include <algorithm>
#include <filesystem>
#include <iostream>
#include <string>
#include <vector>

#include "app/method_catalogue.hpp"
#include "app/montecarlo.hpp"
#include "io/yaml_fields.hpp"

namespace msislab::app {

void add_commands(CLI::App& app, CommandLine& line) {
  add_run_command(app, line);
  add_eval_command(app, line);
  add_simulate_command(app, line);
  add_montecarlo_command(app, line);
  add_sweep_command(app, line);
  add_image_command(app, line);
  add_scans_command(app, line);
  add_footprint_command(app, line);
  add_segment_command(app, line);
  add_plot_command(app, line);
  add_report_command(app, line);
  add_fidelity_command(app, line);
  add_check_command(app, line);
}

std::string unknown_command_message(CLI::App& app, int argc, char** argv) {
  if (argc < 2) return "";
  const std::string word = argv[1];
  if (word.empty() || word[0] == '-') return "";
  std::vector<std::string> names;
  for (const CLI::App* command : app.get_subcommands([](CLI::App*) { return true; })) {
    if (command->check_name(word)) return "";
    names.push_back(command->get_name());
  }
  const std::string nearest = io::closest_key(word, names);
  return "unknown command '" + word + "' (" +
         (nearest.empty() ? "" : "did you mean '" + nearest + "'? ") + "see msislab --help)";
}

void add_force_flag(CLI::App& command, bool& force) {
  command.add_flag("--force", force,
                   "Replace the output folder even when msislab did not write it (its contents "
                   "are lost; an input of the command is never replaced)");
}

std::string method_list() {
  std::string methods;
  for (const std::string& m : MethodCatalogue::builtin_names())
    methods += (methods.empty() ? "" : ", ") + m;
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
