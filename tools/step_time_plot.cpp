// Draws the SLAM back ends' step time against the scans in their state (docs/pose_graph.md,
// "Long missions") from the CSV tools/step_time_figure.sh writes: a header line, then rows
// `backend,scans,ms_per_step`, one series per backend in order of first appearance, log y.
// Usage: msislab_step_time_plot --csv FILE --out FIGURE.png (a new file; an existing one is
// replaced only with --force). Needs an X display; without one it reruns itself under xvfb-run.
#include <CLI/CLI.hpp>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <map>
#include <sstream>
#include <stdexcept>

#include "plot/chart.hpp"
#include "plot/display.hpp"

namespace {

using msislab::plot::ChartSpec;
using msislab::plot::Series;

/// One line and one set of markers per backend, in order of first appearance; throws
/// std::runtime_error on a malformed row.
ChartSpec read_chart(std::istream& in) {
  ChartSpec chart;
  chart.title = "SLAM step time against the scans in the state";
  chart.x_label = "scans in the state";
  chart.y_label = "ms per step (CPU, log scale)";
  chart.log_y = true;
  chart.width_px = 1000;
  chart.height_px = 700;
  const std::uint32_t colours[] = {0x1f77b4, 0xd62728, 0x2ca02c, 0xff7f0e, 0x9467bd, 0x8c564b};
  std::map<std::string, std::size_t> index;
  std::string line;
  std::getline(in, line);  // header
  while (std::getline(in, line)) {
    if (line.empty()) continue;
    std::stringstream row(line);
    std::string backend, scans, ms;
    if (!std::getline(row, backend, ',') || !std::getline(row, scans, ',') ||
        !std::getline(row, ms, ',')) {
      throw std::runtime_error("bad row '" + line + "'");
    }
    auto [it, added] = index.emplace(backend, chart.series.size());
    if (added) {
      Series s;
      s.label = backend;
      s.rgb = colours[(index.size() - 1) % 6];
      chart.series.push_back(s);
      s.label.clear();  // the same colour's markers, not in the legend
      s.style = msislab::plot::SeriesStyle::kPoints;
      s.width_px = 8.0f;
      chart.series.push_back(s);
    }
    for (std::size_t k : {it->second, it->second + 1}) {
      chart.series[k].x.push_back(std::stod(scans));
      chart.series[k].y.push_back(std::stod(ms));
    }
  }
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
    std::ifstream in(csv_path);
    if (!in) {
      std::cerr << "msislab_step_time_plot: cannot read " << csv_path << "\n";
      return 2;
    }
    const ChartSpec chart = read_chart(in);
    msislab::plot::ChartWriter writer;
    writer.write_png(out_path, chart);
    std::cout << "wrote " << out_path << "\n";
  } catch (const std::exception& e) {
    std::cerr << "msislab_step_time_plot: " << e.what() << "\n";
    return 2;
  }
  return 0;
}
