// Draws the SLAM back ends' step time against the scans in their state (docs/pose_graph.md,
// "Long missions") from the CSV tools/step_time_figure.sh writes: a header line, then rows
// `backend,scans,ms_per_step`, one series per backend in order of first appearance, log y.
// Usage: msislab_step_time_plot --csv FILE --out FIGURE.png (a new file; an existing one is
// replaced only with --force). Needs an X display; without one it reruns itself under xvfb-run.
#include <CLI/CLI.hpp>
#include <filesystem>
#include <iostream>
#include <map>

#include "io/text_lines.hpp"
#include "plot/chart.hpp"
#include "plot/display.hpp"

namespace {

using msislab::plot::ChartSpec;
using msislab::plot::Series;

/// One line and one set of markers per backend, in order of first appearance, from the CSV
/// (io::for_each_csv_row: a bad header, row or number is an InputError naming the file and line).
ChartSpec read_chart(const std::string& csv_path) {
  ChartSpec chart;
  chart.title = "SLAM step time against the scans in the state";
  chart.x_label = "scans in the state";
  chart.y_label = "ms per step (CPU, log scale)";
  chart.log_y = true;
  chart.width_px = 1000;
  chart.height_px = 700;
  const std::uint32_t colours[] = {0x1f77b4, 0xd62728, 0x2ca02c, 0xff7f0e, 0x9467bd, 0x8c564b};
  std::map<std::string, std::size_t> index;
  msislab::io::for_each_csv_row(
      csv_path, "backend,scans,ms_per_step", [&](std::string_view line, std::size_t number) {
        const auto fields = msislab::io::split_csv<3>(line, csv_path, number);
        const double scans = msislab::io::parse_finite(fields[1], {csv_path, number, 2, "scans"});
        const double ms =
            msislab::io::parse_finite(fields[2], {csv_path, number, 3, "ms_per_step"});
        auto [it, added] = index.emplace(std::string(fields[0]), chart.series.size());
        if (added) {
          Series s;
          s.label = std::string(fields[0]);
          s.rgb = colours[(index.size() - 1) % 6];
          chart.series.push_back(s);
          s.label.clear();  // the same colour's markers, not in the legend
          s.style = msislab::plot::SeriesStyle::kPoints;
          s.width_px = 8.0f;
          chart.series.push_back(s);
        }
        for (std::size_t k : {it->second, it->second + 1}) {
          chart.series[k].x.push_back(scans);
          chart.series[k].y.push_back(ms);
        }
      });
  return chart;
}

}  // namespace

int main(int argc, char** argv) {
  std::string csv_path;
  std::string out_path;
  bool force = false;
  CLI::App app{"Step time against state size, one line per SLAM back end (PNG)"};
  app.add_option("--csv", csv_path, "backend,scans,ms_per_step rows")->required();
  app.add_option("--out", out_path, "PNG to write")->required();
  app.add_flag("--force", force, "replace an existing --out");
  CLI11_PARSE(app, argc, argv);
  try {
    if (std::filesystem::exists(out_path) && !force) {
      std::cerr << "msislab_step_time_plot: " << out_path << " exists (--force replaces it)\n";
      return 2;
    }
    if (!msislab::plot::x_display_available()) msislab::plot::rerun_under_xvfb(argc, argv);
    const ChartSpec chart = read_chart(csv_path);
    msislab::plot::ChartWriter writer;
    writer.write_png(out_path, chart);
    std::cout << "wrote " << out_path << "\n";
  } catch (const std::exception& e) {
    std::cerr << "msislab_step_time_plot: " << e.what() << "\n";
    return 2;
  }
  return 0;
}
