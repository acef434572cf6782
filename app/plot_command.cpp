#include "app/plot_command.hpp"

#include <CLI/CLI.hpp>
#include <algorithm>
#include <filesystem>
#include <iomanip>
#include <iostream>
#include <memory>

#include "app/cli.hpp"
#include "app/method_catalogue.hpp"
#include "dataset/sonar_revolution.hpp"
#include "io/atomic_file.hpp"
#include "io/output_guard.hpp"
#include "plot/acoustic_image.hpp"
#include "plot/display.hpp"
#include "report/plot_figures.hpp"
#include "report/plot_inputs.hpp"
#include "report/sweep_figures.hpp"

namespace msislab::app {

namespace fs = std::filesystem;

namespace {

class FigureWriter {
 public:
  FigureWriter(const report::PlotOptions& options, const report::MethodStyles& styles)
      : options_(options), styles_(styles) {}

  void chart(const fs::path& dir, const std::string& name, const plot::ChartSpec& spec) {
    charts_.write_png(prepare(dir, name), spec);
  }
  /// trajectory.png and (with truth) error.png of one result, into its figures/.
  void result(const report::ResultData& r) {
    const fs::path dir = fs::path(r.dir) / "figures";
    chart(dir, "trajectory.png",
          report::trajectory_chart(styles_, r, options_.ellipse_every, options_.width_px,
                                   options_.height_px));
    if (!r.errors.empty()) {
      chart(dir, "error.png",
            report::error_chart(styles_, {&r}, options_.width_px, options_.height_px));
    }
  }
  void acoustic_image(const fs::path& dir, const dataset::SonarRevolution& revolution) {
    const std::string dataset =
        fs::path(revolution.dataset_dir).lexically_normal().filename().string();
    plot::write_acoustic_figure(
        prepare(dir, "acoustic_image.png"), revolution.beams, revolution.setup, revolution.mount,
        "Sonar revolution " + std::to_string(revolution.index) + " of " + dataset,
        options_.width_px, options_.height_px);
  }
  const std::vector<std::string>& written() const { return written_; }

 private:
  /// Claims the figures folder (created with msislab's marker, or one it wrote before) and
  /// records the file (written atomically by the drawing call).
  std::string prepare(const fs::path& dir, const std::string& name) {
    io::claim_output_folder({dir.string(), "figures", "plot", {}, false});
    written_.push_back((dir / name).string());
    return written_.back();
  }

  const report::PlotOptions& options_;
  const report::MethodStyles& styles_;
  plot::ChartWriter charts_;
  std::vector<std::string> written_;
};

/// A figure per result named after its method (its folder when two share a method).
std::string comparison_name(const report::PlotInputs& in, const report::ResultData& r) {
  const auto same_method =
      std::count_if(in.results.begin(), in.results.end(),
                    [&](const report::ResultData& o) { return o.method == r.method; });
  return (same_method > 1 ? r.name : r.method) + ".png";
}

}  // namespace

std::vector<std::string> draw_plot(const report::PlotInputs& in,
                                   const report::MethodStyles& styles) {
  const report::PlotOptions& options = in.options;
  const fs::path figures = fs::path(options.dir) / "figures";
  FigureWriter writer(options, styles);
  if (in.comparison) {
    std::vector<const report::ResultData*> with_errors;
    for (const report::ResultData& r : in.results) {
      writer.chart(figures, comparison_name(in, r),
                   report::trajectory_chart(styles, r, options.ellipse_every, options.width_px,
                                            options.height_px));
      if (!r.errors.empty()) with_errors.push_back(&r);
    }
    if (!with_errors.empty()) {
      writer.chart(figures, "errors.png",
                   report::error_chart(styles, with_errors, options.width_px, options.height_px));
    }
  }
  for (const report::ResultData& r : in.results) writer.result(r);
  if (!in.nees.empty()) {
    writer.chart(figures, "nees.png",
                 report::nees_chart(styles, in.nees, options.width_px, options.height_px));
  }
  if (!in.error_spread.empty()) {
    writer.chart(
        figures, "error_spread.png",
        report::error_spread_chart(styles, in.error_spread, options.width_px, options.height_px));
  }
  if (!in.error_histograms.empty()) {
    writer.chart(figures, "error_distribution.png",
                 report::error_distribution_chart(styles, in.error_histograms, options.width_px,
                                                  options.height_px));
  }
  if (in.sweep) {
    for (std::size_t k = 0; k < in.sweep->keys.size(); ++k) {
      std::string stem = in.sweep->keys[k];
      std::replace(stem.begin(), stem.end(), '.', '_');
      for (const char* metric : {"mean_error", "anees", "paired_difference", "linearisation"}) {
        if (!report::sweep_has_metric(*in.sweep, metric)) continue;
        writer.chart(
            figures, "sweep_" + stem + "_" + metric + ".png",
            report::sweep_chart(styles, *in.sweep, k, metric, options.width_px, options.height_px));
      }
    }
  }
  if (in.revolution) writer.acoustic_image(figures, *in.revolution);
  return writer.written();
}

std::vector<std::string> plot(const report::PlotOptions& options,
                              const report::MethodStyles& styles) {
  return draw_plot(report::load_plot_inputs(options), styles);
}

void add_plot_command(CLI::App& app, CommandLine& line) {
  auto options = std::make_shared<report::PlotOptions>();
  CLI::App* command = app.add_subcommand(
      "plot",
      "Draw the figures of a result, comparison or Monte Carlo directory as PNG into DIR/figures/ "
      "(VTK: needs an X display, else reruns itself under xvfb-run)");
  command
      ->add_option("DIR", options->dir,
                   "A result directory (trajectory.tum), a folder of result directories, or a "
                   "Monte Carlo directory (nees.csv)")
      ->required();
  command->add_option("--dataset,-d", options->dataset_dir,
                      "Dataset directory for the truth and the acoustic image (default: the one "
                      "recorded in metrics.json)");
  command
      ->add_option("--ellipse-every", options->ellipse_every,
                   "Draw the 2-sigma ellipse of every k-th scan (default: about 25 per figure)")
      ->check(CLI::PositiveNumber);
  command->add_option("--width", options->width_px, "Figure width in pixels")
      ->check(CLI::Range(400, 4000));
  command->add_option("--height", options->height_px, "Figure height in pixels")
      ->check(CLI::Range(300, 4000));
  command
      ->add_option("--revolution,-r", options->revolution,
                   "Sonar revolution of the acoustic image (default: the middle one)")
      ->check(CLI::NonNegativeNumber);
  auto methods_file = std::make_shared<std::string>();
  command->add_option("--methods-file", *methods_file,
                      "Methods file (YAML): titles, colours and line styles of external methods "
                      "(without it they are drawn under their names)");
  // Reads every input first (bad input fails without a display), then draws; VTK needs an X
  // display, so without one the command runs again under xvfb-run.
  command->callback([options, methods_file, &line] {
    const report::MethodStyles styles(
        MethodCatalogue::with_methods_file(*methods_file).methods_file());
    const report::PlotInputs inputs = report::load_plot_inputs(*options);
    if (!plot::x_display_available()) plot::rerun_under_xvfb(line.argc, line.argv);
    for (const std::string& file : draw_plot(inputs, styles)) std::cout << "wrote " << file << "\n";
    std::cout << std::flush;
  });
}

}  // namespace msislab::app
