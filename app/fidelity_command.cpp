#include "app/fidelity_command.hpp"

#include <CLI/CLI.hpp>
#include <filesystem>
#include <iostream>
#include <memory>

#include "app/cli.hpp"
#include "io/atomic_file.hpp"
#include "io/output_guard.hpp"
#include "plot/chart.hpp"
#include "plot/display.hpp"
#include "report/fidelity_figures.hpp"

namespace msislab::app {

namespace fs = std::filesystem;

namespace {

io::OutputRequest fidelity_output(const report::FidelityOptions& options) {
  return {options.out_dir,
          "fidelity report",
          "fidelity",
          {options.real_dir, options.sim_dir},
          options.force};
}

std::string folder_name(const std::string& dir) {
  fs::path path = fs::absolute(dir).lexically_normal();
  if (path.filename().empty()) path = path.parent_path();
  return path.filename().string();
}

report::FigureSide figure_side(const report::FidelitySide& side, const std::string& role) {
  return {role,        folder_name(side.dir),  &side.stats,
          &side.beams, side.calibration.sonar, side.revolution};
}

}  // namespace

std::vector<std::string> write_fidelity(const report::FidelityReport& compared) {
  io::StagedFolder staged(fidelity_output(compared.options));
  const fs::path partial(staged.path());
  io::create_output_dir((partial / "figures").string());
  const double range_m = compared.real.setup.range_m;
  const report::FigureSide real = figure_side(compared.real, "Real"),
                           sim = figure_side(compared.sim, "Simulated");
  const plot::ChartWriter charts;
  charts.write_png((partial / "figures" / "ranges.png").string(),
                   report::range_charts(real, sim, range_m));
  charts.write_png((partial / "figures" / "revolution.png").string(),
                   report::revolution_charts(real, sim, range_m));
  io::write_json_file((partial / "fidelity.json").string(), report::fidelity_json(compared),
                      report::kFidelityJsonLayout);
  io::write_file_atomically((partial / "fidelity.md").string(),
                            [&](std::ostream& out) { out << report::fidelity_page(compared); });
  staged.commit();
  const fs::path out = compared.options.out_dir;
  return {(out / "fidelity.md").string(), (out / "fidelity.json").string(),
          (out / "figures" / "ranges.png").string(), (out / "figures" / "revolution.png").string()};
}

void add_fidelity_command(CLI::App& app, CommandLine& line) {
  auto options = std::make_shared<report::FidelityOptions>();
  CLI::App* fidelity = app.add_subcommand(
      "fidelity",
      "Compare a simulated dataset with the real one, statistic by statistic, from their "
      "detections: prints a Markdown table (values, sim / real, KS distance); --out also writes "
      "fidelity.md, fidelity.json and figures (VTK: needs an X display, else reruns itself under "
      "xvfb-run)");
  fidelity
      ->add_option("REAL_DATASET", options->real_dir,
                   "Real dataset directory (*_detections.csv[.gz], *_IS_timestamps.log)")
      ->required();
  fidelity
      ->add_option("SIM_DATASET", options->sim_dir,
                   "Simulated dataset directory, in the same formats and sonar setup")
      ->required();
  fidelity->add_option("--out,-o", options->out_dir,
                       "Report folder (fidelity.md, fidelity.json, figures/), replaced whole");
  add_force_flag(*fidelity, options->force);
  fidelity->add_option("--revolution-real", options->revolution_real,
                       "Keyframe of the real detections drawn in revolution.png (default: the "
                       "middle one)");
  fidelity->add_option("--revolution-sim", options->revolution_sim,
                       "Keyframe of the simulated detections drawn (default: the one nearest in "
                       "time to the real one drawn when the runs overlap in time, else the middle "
                       "one)");
  // Checks the output folder, reads both datasets and computes the table first (bad input fails
  // without a display); the figures of --out need one, so without it the command runs again under
  // xvfb-run.
  fidelity->callback([options, &line] {
    if (!options->out_dir.empty()) io::check_output_folder(fidelity_output(*options));
    const report::FidelityReport compared = report::compare_datasets(*options);
    if (!options->out_dir.empty() && !plot::x_display_available()) {
      plot::rerun_under_xvfb(line.argc, line.argv);
    }
    std::cout << report::fidelity_markdown(compared.table);
    if (!options->out_dir.empty()) {
      std::cout << "\n";
      for (const std::string& file : write_fidelity(compared))
        std::cout << "wrote " << file << "\n";
    }
    std::cout << std::flush;
  });
}

}  // namespace msislab::app
