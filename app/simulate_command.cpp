#include "app/simulate_command.hpp"

#include <CLI/CLI.hpp>
#include <algorithm>
#include <chrono>
#include <iomanip>
#include <iostream>
#include <memory>
#include <thread>

#include "app/cli.hpp"
#include "dataset/sim_dataset.hpp"
#include "io/input_error.hpp"
#include "io/output_guard.hpp"
#include "io/text_lines.hpp"
#include "settings/scenario_scene.hpp"
#include "sim/simulator.hpp"

namespace msislab::app {

namespace {
using Clock = std::chrono::steady_clock;

double seconds_since(Clock::time_point start) {
  return std::chrono::duration<double>(Clock::now() - start).count();
}

}  // namespace

SimulateSummary simulate(const SimulateOptions& options) {
  const auto t_start = Clock::now();
  settings::CheckedScenario checked = settings::read_checked_scenario(options.scenario_path);
  sim::Scenario& scenario = checked.scenario;
  if (options.seed) scenario.seed = *options.seed;
  const io::OutputRequest out{options.out_dir,
                              "dataset",
                              "simulate",
                              {options.scenario_path, scenario.scene.mesh_path},
                              options.force};
  io::check_output_folder(out);  // before the rendering, which may take minutes
  for (const std::string& warning : checked.warnings) std::cerr << "msislab: " << warning << '\n';
  const sim::TriangleMesh& mesh = checked.mesh;
  std::unique_ptr<sim::Scene> scene;
  try {
    scene = std::make_unique<sim::Scene>(mesh, scenario.scene.surface);
  } catch (const std::exception& e) {
    io::fail_file(scenario.scene.mesh_path, std::string("cannot build the scene: ") + e.what());
  }
  const int threads = options.threads > 0
                          ? options.threads
                          : static_cast<int>(std::max(1u, std::thread::hardware_concurrency()));

  const auto t_render = Clock::now();
  const sim::SimulationResult result = sim::simulate(scenario, *scene, threads);
  SimulateSummary summary;
  summary.render_s = seconds_since(t_render);
  dataset::write_simulated_dataset(out, scenario, result,
                                   io::read_whole_file(options.scenario_path));
  summary.beams = result.beams.size();
  summary.dvl_samples = result.dvl.size();
  summary.duration_s = result.truth.end_s() - result.truth.start_s();
  summary.rays_per_beam = static_cast<std::size_t>(scenario.sonar.rays_horizontal) *
                          static_cast<std::size_t>(scenario.sonar.rays_vertical);
  summary.total_s = seconds_since(t_start);
  return summary;
}

void add_simulate_command(CLI::App& app, CommandLine&) {
  auto options = std::make_shared<SimulateOptions>();
  CLI::App* command = app.add_subcommand(
      "simulate", "Render a synthetic dataset (St. Pere log formats plus truth/) from a scenario");
  command->add_option("SCENARIO", options->scenario_path, "Scenario YAML (docs/simulator.md)")
      ->required();
  command->add_option("--out,-o", options->out_dir, "Dataset directory to write")->required();
  command->add_option("--seed", options->seed, "Seed overriding the scenario's");
  add_force_flag(*command, options->force);
  command
      ->add_option("--threads,-j", options->threads,
                   "Worker threads (default: one per hardware thread; the output is the same "
                   "for any count)")
      ->check(CLI::NonNegativeNumber);
  command->callback([options] {
    const SimulateSummary s = simulate(*options);
    std::cout << std::fixed << std::setprecision(2) << "wrote " << options->out_dir << ": "
              << s.beams << " beams (" << s.rays_per_beam << " rays each), " << s.dvl_samples
              << " DVL samples over " << s.duration_s << " s; simulated in " << s.render_s << " s ("
              << s.duration_s / std::max(s.render_s, 1e-9) << "x real time), " << s.total_s
              << " s in all" << std::endl;
  });
}

}  // namespace msislab::app
