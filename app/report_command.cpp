#include "app/report_command.hpp"

#include <unistd.h>

#include <CLI/CLI.hpp>
#include <algorithm>
#include <cmath>
#include <filesystem>
#include <iomanip>
#include <iostream>
#include <memory>
#include <sstream>

#include "app/cli.hpp"
#include "app/methods.hpp"
#include "app/plot_figures.hpp"
#include "app/plot_inputs.hpp"
#include "io/atomic_file.hpp"
#include "io/input_error.hpp"
#include "io/text_lines.hpp"
#include "slam/scan_matching.hpp"

namespace msislab::app {

namespace fs = std::filesystem;

namespace {

/// A table cell: the value with `decimals` decimals, "n/a" when it is not finite or missing.
std::string fixed(double value, int decimals) {
  return std::isfinite(value) ? io::format_fixed(value, decimals) : "n/a";
}

std::string fixed(const std::optional<double>& value, int decimals) {
  return value ? fixed(*value, decimals) : "n/a";
}

std::string percent(const std::optional<double>& fraction) {
  return fraction ? fixed(100.0 * *fraction, 1) + " %" : "n/a";
}

/// PNG files of DIR/figures, sorted; InputError when the folder is missing or holds none.
std::vector<std::string> figures_of(const std::string& dir) {
  const fs::path folder = fs::path(dir) / "figures";
  std::vector<std::string> names;
  std::error_code ec;
  for (const auto& entry : fs::directory_iterator(folder, ec)) {
    if (entry.is_regular_file() && entry.path().extension() == ".png") {
      names.push_back(entry.path().filename().string());
    }
  }
  if (names.empty()) {
    io::fail_file(folder.string(), "no figures (draw them first: msislab plot " + dir + ")");
  }
  std::sort(names.begin(), names.end());
  return names;
}

std::optional<double> segment_of(
    const std::vector<std::pair<std::string, std::optional<double>>>& s, const std::string& name) {
  for (const auto& [n, value] : s) {
    if (n == name) return value;
  }
  return std::nullopt;
}

/// Segment names in order of first appearance.
template <typename Rows, typename Segments>
std::vector<std::string> segment_names(const Rows& rows, Segments segments) {
  std::vector<std::string> names;
  for (const auto& row : rows) {
    for (const auto& [name, value] : segments(row)) {
      if (std::find(names.begin(), names.end(), name) == names.end()) names.push_back(name);
    }
  }
  return names;
}

const RunMetrics* find_method(const ResultFolder& folder, const std::string& method) {
  for (const RunMetrics& m : folder.results) {
    if (m.method == method) return &m;
  }
  return nullptr;
}

void table_one(std::ostringstream& md, const ResultFolder& folder, const std::string& truth_name) {
  const std::vector<std::string> segments = segment_names(
      folder.results, [](const RunMetrics& m) -> const auto& { return m.segments; });
  const bool with_nees = std::any_of(folder.results.begin(), folder.results.end(),
                                     [](const RunMetrics& m) { return m.anees.has_value(); });
  md << "| method | mean error [m] |";
  for (const std::string& s : segments) md << " " << s << " [m] |";
  md << " final [m] | max [m] | scans | matches accepted |" << (with_nees ? " ANEES |" : "")
     << " run time [s] |\n| --- | ---: |";
  for (std::size_t i = 0; i < segments.size(); ++i) md << " ---: |";
  md << " ---: | ---: | ---: | ---: |" << (with_nees ? " ---: |" : "") << " ---: |\n";
  for (const RunMetrics& m : folder.results) {
    md << "| " << method_title(m.method) << " | **" << fixed(m.errors.mean_m, 2) << "** |";
    for (const std::string& s : segments) md << " " << fixed(segment_of(m.segments, s), 2) << " |";
    md << " " << fixed(m.errors.final_m, 2) << " | " << fixed(m.errors.max_m, 2) << " | "
       << (m.scans > 0 ? std::to_string(m.scans) : "") << " | "
       << (m.matches_accepted > 0 ? std::to_string(m.matches_accepted) : "") << " |";
    if (with_nees) md << " " << fixed(m.anees, 2) << " |";
    md << " " << fixed(m.runtime_s, 2) << " |\n";
  }
  md << "\nErrors: planar distance to the " << truth_name
     << " at its time stamps, the estimate interpolated, no alignment (docs/formats.md).";
  if (with_nees) {
    md << " ANEES: the NEES of the 3-DOF scan pose averaged over the scans (3 when consistent).";
  }
  md << "\n";
  const RunMetrics* rc = find_method(folder, "robocentric");
  const RunMetrics* wc = find_method(folder, "worldcentric");
  const RunMetrics* dr = find_method(folder, "deadreckoning");
  if (rc && wc) {
    md << "\n- Robocentric against world-centric SLAM: " << fixed(rc->errors.mean_m, 2)
       << " against " << fixed(wc->errors.mean_m, 2) << " m mean error"
       << (std::abs(rc->errors.mean_m - wc->errors.mean_m) < 0.01 ? " (the same within 1 cm)" : "")
       << ".\n";
  }
  // A back end with an online estimate (the pose graph): its smoothed trajectory beside it.
  for (const RunMetrics& m : folder.results) {
    const auto smoothed =
        std::find_if(m.diagnostics.begin(), m.diagnostics.end(),
                     [](const auto& d) { return d.first == "smoothed_mean_error_m"; });
    if (smoothed == m.diagnostics.end()) continue;
    md << "- " << method_title(m.method) << ": " << fixed(smoothed->second, 2)
       << " m mean error smoothed (trajectory_smoothed.tum), " << fixed(m.errors.mean_m, 2)
       << " m online (the table, docs/pose_graph.md).\n";
  }
  if (rc && dr) {
    md << "- Robocentric SLAM against dead reckoning: " << fixed(rc->errors.mean_m, 2)
       << " against " << fixed(dr->errors.mean_m, 2) << " m mean error ("
       << fixed(100.0 * (rc->errors.mean_m / dr->errors.mean_m - 1.0), 0) << " %)";
    for (const std::string& s : segments) {
      const auto a = segment_of(rc->segments, s), b = segment_of(dr->segments, s);
      if (a && b) md << "; " << s << " " << fixed(*a, 2) << " against " << fixed(*b, 2) << " m";
    }
    md << ".\n";
  }
}

/// The figures `msislab plot` draws, in the order the page shows them, with their captions
/// (the (a)-(d) and the NEES figure); `truth` names the reference.
std::vector<std::pair<std::string, std::string>> figure_captions(const std::string& truth) {
  return {{"deadreckoning.png",
           "(a) Dead reckoning against the " + truth + ", with the sonar points it places"},
          {"worldcentric.png", "(b) World-centric SLAM against the " + truth +
                                   ", 2-sigma ellipses of the scan poses and the map points"},
          {"robocentric.png", "(c) Robocentric SLAM against the " + truth +
                                  ", 2-sigma ellipses of the scan poses and the map points"},
          {"errors.png", "(d) Position error against time, every method"},
          {"posegraph.png", "The pose graph (online) against the " + truth +
                                ", 2-sigma ellipses of the scan poses and the map points"},
          {"integration.png", "Plain DVL integration against the " + truth},
          {"acoustic_image.png", "One revolution of the raw sonar log (acoustic image)"},
          {"nees.png", "Run-averaged NEES of the scan pose per scan step, with the 95% bounds"},
          {"error_spread.png",
           "Position error against time over the runs: mean, and 5-95 % of the runs dotted"},
          {"error_distribution.png",
           "Distribution of the position error, every run sampled once a second"}};
}

void figure_list(std::ostringstream& md, const std::string& figures_dir, const std::string& label,
                 const std::string& truth, const std::vector<std::string>& figures) {
  std::vector<std::pair<std::string, std::string>> shown;
  for (const auto& [name, caption] : figure_captions(truth)) {
    if (std::find(figures.begin(), figures.end(), name) != figures.end()) {
      shown.emplace_back(name, caption);
    }
  }
  for (const std::string& name : figures) {
    const bool known = std::any_of(shown.begin(), shown.end(),
                                   [&](const auto& figure) { return figure.first == name; });
    if (!known) shown.emplace_back(name, fs::path(name).stem().string());
  }
  for (const auto& [name, caption] : shown) {
    md << "\n**" << caption << "**\n\n![" << caption << "](" << figures_dir << "/" << label << "_"
       << name << ")\n";
  }
}

/// A Monte Carlo folder's section; `first`: the page's consistency test, else titled by its
/// scenario.
void montecarlo_section(std::ostringstream& md, const MonteCarloFolder& mc,
                        const std::string& figures_dir, bool first) {
  const io::MonteCarloManifest& m = mc.manifest;
  const std::string scenario = fs::path(m.scenario_source).filename().string();
  md << "\n## Monte Carlo consistency" << (first ? "" : ": `" + scenario + "`") << "\n\n"
     << m.runs << " seeded runs of the scenario `" << scenario << "` (seeds " << m.first_seed
     << " to " << m.first_seed + static_cast<std::uint64_t>(m.runs) - 1
     << "), each simulated and run by every method; `" << mc.dir << "`.\n\n";
  const std::vector<std::string> segments = segment_names(
      mc.methods, [](const io::StoredSummary& s) -> const auto& { return s.summary.segments; });
  md << "| method | runs | failed | mean error [m] |";
  for (const std::string& s : segments) md << " " << s << " [m] |";
  md << " ANEES | scan steps with NEES in the 95% bounds | bounds | run time per run [s] |\n"
     << "| --- | ---: | ---: | ---: |";
  for (std::size_t i = 0; i < segments.size(); ++i) md << " ---: |";
  md << " ---: | ---: | --- | ---: |\n";
  for (const io::StoredSummary& stored : mc.methods) {
    const MethodSummary& s = stored.summary;
    md << "| " << method_title(s.method) << " | " << s.runs << " | " << s.failed << " | "
       << fixed(s.mean_error_m, 2) << " |";
    for (const std::string& name : segments) {
      md << " " << fixed(segment_of(s.segments, name), 2) << " |";
    }
    std::string bounds = "n/a";
    if (s.runs > 0) {
      const auto [lower, upper] = average_chi2_bounds(s.runs, 3, 0.05);
      bounds = "[" + fixed(lower, 2) + ", " + fixed(upper, 2) + "]";
    }
    md << " " << fixed(s.anees, 2) << " | " << percent(s.nees_in_bounds_fraction) << " of "
       << stored.nees_scans << " | " << bounds << " | "
       << fixed(s.runs > 0 ? s.runtime_s / s.runs : NAN, 2) << " |\n";
  }
  md << "\nThe NEES of the 3-DOF scan pose is averaged over the runs at each scan step; N runs "
        "times that average is chi-square with 3N degrees of freedom for a consistent filter, so "
        "the two-sided 95% bounds apply to each step (docs/trajectory_slam.md). The ANEES averages "
        "it over the steps too.\n";
  const MethodSummary* rc = nullptr;
  const MethodSummary* wc = nullptr;
  for (const io::StoredSummary& stored : mc.methods) {
    const MethodSummary& s = stored.summary;
    if (s.method == "robocentric") rc = &s;
    if (s.method == "worldcentric") wc = &s;
  }
  if (rc && wc && rc->anees && wc->anees && rc->nees_in_bounds_fraction &&
      wc->nees_in_bounds_fraction) {
    const double da = *rc->anees - *wc->anees;
    const double df = *rc->nees_in_bounds_fraction - *wc->nees_in_bounds_fraction;
    std::string verdict;
    if (std::abs(da) <= 0.05 * *wc->anees && std::abs(df) <= 0.02) {
      verdict = "equally consistent";
    } else if (std::abs(*rc->anees - 3.0) < std::abs(*wc->anees - 3.0) && df >= 0.0) {
      verdict = "the more consistent one";
    } else if (std::abs(*rc->anees - 3.0) > std::abs(*wc->anees - 3.0) && df <= 0.0) {
      verdict = "the less consistent one";
    } else {
      verdict = "neither clearly more nor less consistent";
    }
    md << "\n- **Robocentric against world-centric**: ANEES " << fixed(rc->anees, 2) << " against "
       << fixed(wc->anees, 2) << ", " << percent(rc->nees_in_bounds_fraction) << " against "
       << percent(wc->nees_in_bounds_fraction)
       << " of the steps in bounds: the robocentric filter is " << verdict
       << " here (the paper argues it is the more consistent).\n";
  }
  figure_list(md, figures_dir, mc.label, "truth", mc.figures);
}

std::string scientific(const std::optional<double>& value) {
  if (!value) return "n/a";
  std::ostringstream out;
  out << std::setprecision(1) << std::scientific << *value;
  return out.str();
}

/// Metres in millimetres, one decimal, without a "-0.0".
std::string millimetres(double metres) {
  const std::string text = fixed(1000.0 * metres, 1);
  return text == "-0.0" ? "0.0" : text;
}

/// A sweep's sweep.csv as a table: a row per cell, per method its mean error and ANEES, each
/// further method's paired difference to the first with its 95 % interval, and the linearisation
/// errors when measured; then the cells where the paired difference is beyond the noise.
void sweep_section(std::ostringstream& md, const SweepFolder& sweep) {
  const io::SweepTable& t = sweep.table;
  const std::string name = fs::path(sweep.dir).lexically_normal().filename().string();
  std::vector<std::string> methods;
  std::vector<int> cells;
  bool linearisation = false;
  for (const io::SweepRow& r : t.rows) {
    if (std::find(methods.begin(), methods.end(), r.method) == methods.end())
      methods.push_back(r.method);
    if (std::find(cells.begin(), cells.end(), r.cell) == cells.end()) cells.push_back(r.cell);
    linearisation |= r.linearisation_pose.has_value();
  }
  if (methods.empty()) io::fail_file(sweep.dir + "/sweep.csv", "no rows (the sweep has not run)");
  const auto row_of = [&](int cell, const std::string& method) -> const io::SweepRow* {
    for (const io::SweepRow& r : t.rows) {
      if (r.cell == cell && r.method == method) return &r;
    }
    return nullptr;
  };
  md << "\n## Sweep: `" << name << "`\n\n"
     << "`" << sweep.dir << "/sweep.csv`, " << cells.size()
     << " cells. Mean error over the runs; the paired difference is each run's mean error minus "
     << method_title(methods.front())
     << "'s on the same simulated data, averaged, with its 95 % interval (docs/formats.md)"
     << (linearisation ? "; epsilon is the linearisation error (docs/robocentric.md)" : "")
     << ".\n\n|";
  std::string rule = "|";
  for (const std::string& key : t.keys) {
    md << " " << key.substr(key.rfind('.') + 1) << " |";
    rule += " ---: |";
  }
  for (const std::string& m : methods) {
    md << " " << method_title(m) << " [m] |";
    rule += " ---: |";
  }
  for (std::size_t i = 1; i < methods.size(); ++i) {
    md << " " << method_title(methods[i]) << " minus " << method_title(methods.front())
       << " [mm] |";
    rule += " ---: |";
  }
  md << " ANEES |";
  rule += " ---: |";
  if (linearisation) {
    md << " epsilon: match update | inversion | pose read-out |";
    rule += " ---: | ---: | ---: |";
  }
  md << "\n" << rule << "\n";
  std::vector<std::string> beyond;
  for (const int cell : cells) {
    const io::SweepRow* first = row_of(cell, methods.front());
    md << "|";
    for (std::size_t k = 0; k < t.keys.size(); ++k) {
      md << " " << (first ? first->values[k] : "") << " |";
    }
    std::string anees, match, inversion, pose;
    for (const std::string& m : methods) {
      const io::SweepRow* r = row_of(cell, m);
      md << " " << (r ? fixed(r->mean_error_m, 3) : "n/a") << " |";
      const std::string sep = m == methods.front() ? "" : " / ";
      anees += sep + (r ? fixed(r->anees, 2) : "n/a");
      if (!r) continue;
      match += sep + scientific(r->linearisation_observation);
      pose += sep + scientific(r->linearisation_pose);
      if (r->linearisation_inversion) {
        inversion += (inversion.empty() ? "" : " / ") + scientific(r->linearisation_inversion);
      }
    }
    for (std::size_t i = 1; i < methods.size(); ++i) {
      const io::SweepRow* r = row_of(cell, methods[i]);
      if (!r || !r->paired_difference_m) {
        md << " n/a |";
        continue;
      }
      const bool significant = *r->paired_ci95_lower_m > 0.0 || *r->paired_ci95_upper_m < 0.0;
      md << " " << (significant ? "**" : "") << millimetres(*r->paired_difference_m) << " ["
         << millimetres(*r->paired_ci95_lower_m) << ", " << millimetres(*r->paired_ci95_upper_m)
         << "]" << (significant ? "**" : "") << " |";
      if (significant) beyond.push_back("cell " + std::to_string(cell) + " (" + methods[i] + ")");
    }
    md << " " << anees << " |";
    if (linearisation) {
      md << " " << match << " | " << (inversion.empty() ? "n/a" : inversion) << " | " << pose
         << " |";
    }
    md << "\n";
  }
  md << "\nPaired differences beyond the Monte Carlo noise (95 % interval without 0, in bold): ";
  if (beyond.empty()) {
    md << "none.\n";
  } else {
    for (std::size_t i = 0; i < beyond.size(); ++i) md << (i ? ", " : "") << beyond[i];
    md << ".\n";
  }
}

/// Copies `from` to `to` whole; InputError naming the source on failure.
void copy_figure(const fs::path& from, const fs::path& to) {
  std::error_code ec;
  fs::copy_file(from, to, fs::copy_options::overwrite_existing, ec);
  if (ec) io::fail_file(from.string(), "cannot copy to " + to.string() + ": " + ec.message());
}

}  // namespace

ResultFolder read_result_folder(const std::string& dir, const std::string& label) {
  if (!fs::is_directory(dir)) io::fail_file(dir, "not a directory");
  ResultFolder folder;
  folder.label = label;
  folder.dir = dir;
  for (const fs::path& sub : result_subdirs(dir)) {
    if (!fs::is_regular_file(sub / "metrics.json")) continue;  // run without truth: no scores
    const io::StoredMetrics stored = io::read_metrics_json((sub / "metrics.json").string());
    if (folder.dataset.empty()) folder.dataset = stored.dataset_dir;
    folder.results.push_back(stored.metrics);
  }
  if (folder.results.empty()) {
    io::fail_file(dir, "no result directories (subdirectories with a metrics.json)");
  }
  std::stable_sort(folder.results.begin(), folder.results.end(),
                   [](const RunMetrics& a, const RunMetrics& b) {
                     return method_rank(a.method) < method_rank(b.method);
                   });
  folder.figures = figures_of(dir);
  return folder;
}

MonteCarloFolder read_montecarlo_folder(const std::string& dir) {
  if (!fs::is_directory(dir)) io::fail_file(dir, "not a directory");
  MonteCarloFolder mc;
  mc.label = "montecarlo";
  mc.dir = dir;
  mc.manifest = io::read_manifest_json((fs::path(dir) / "montecarlo.json").string());
  const fs::path summary = fs::path(dir) / "summary.json";
  if (!fs::is_regular_file(summary)) {
    io::fail_file(summary.string(), "missing (the Monte Carlo has not finished or been merged)");
  }
  mc.methods = io::read_summary_json(summary.string());
  mc.figures = figures_of(dir);
  return mc;
}

std::string results_markdown(const ResultsReport& report) {
  std::ostringstream md;
  md << "# Results\n\n"
        "Generated by `msislab report` from the result folders named below; do not edit it by "
        "hand. `tools/results.sh` regenerates docs/results.md (every method on the simulated St. "
        "Pere replica and on the real St. Pere dataset, the Monte Carlo consistency test on the "
        "replica and on the failure scenarios, the figures); `tools/main.sh` writes the same page "
        "without the Monte Carlo as "
        "out/results.md. The paper (Burguera, Gonzalez, Oliver) reports on the real data a "
        "mean error of **1.15 m** for the robocentric and **2.05 m** for the world-centric "
        "trajectory (its Table I). Why the two filters agree here: docs/trajectory_slam.md; "
        "whether they differ in any regime (heading and DVL noise, revolution period, EKF "
        "against IEKF, compass, loop length, 20 paired runs a cell): docs/robocentric.md, whose "
        "sweeps close this page when tools/robocentric_study.sh has filled out/study.\n";
  const auto section = [&](const std::optional<ResultFolder>& folder, const std::string& title,
                           const std::string& truth_name) {
    md << "\n## " << title << "\n\n";
    if (!folder) {
      md << "Not run (the data was not available when this page was written).\n";
      return;
    }
    md << "Results in `" << folder->dir << "`";
    if (!folder->dataset.empty()) {
      md << ", dataset `" << fs::path(folder->dataset).filename().string() << "`";
    }
    md << ".\n\n";
    table_one(md, *folder, truth_name);
    figure_list(md, report.figures_dir_name, folder->label, truth_name, folder->figures);
  };
  section(report.sim, "Table I on the simulated St. Pere replica", "simulation truth");
  section(report.real, "Table I on the real St. Pere dataset", "GPS track");
  if (report.real) {
    md << "\nThe paper on the same data: robocentric 1.15 m, world-centric 2.05 m mean error.\n";
  }
  if (report.montecarlo.empty()) md << "\n## Monte Carlo consistency\n\nNot run.\n";
  for (std::size_t i = 0; i < report.montecarlo.size(); ++i) {
    montecarlo_section(md, report.montecarlo[i], report.figures_dir_name, i == 0);
  }
  for (const SweepFolder& sweep : report.sweeps) sweep_section(md, sweep);
  return md.str();
}

ReportOutcome write_report(const ReportOptions& options) {
  if (options.out_path.empty()) throw io::InputError("report: no output page given");
  if (options.sim_dir.empty() && options.real_dir.empty() && options.montecarlo_dirs.empty() &&
      options.sweep_dirs.empty()) {
    throw io::InputError("report: nothing to report (give --sim, --real, --montecarlo or --sweep)");
  }
  ResultsReport report;
  const fs::path page = fs::absolute(options.out_path).lexically_normal();
  report.figures_dir_name = page.stem().string();
  if (!options.sim_dir.empty()) report.sim = read_result_folder(options.sim_dir, "sim");
  if (!options.real_dir.empty()) report.real = read_result_folder(options.real_dir, "real");
  for (const std::string& dir : options.montecarlo_dirs) {
    MonteCarloFolder mc = read_montecarlo_folder(dir);
    if (!report.montecarlo.empty()) {
      mc.label += "_" + fs::path(mc.manifest.scenario_source).stem().string();
      for (const MonteCarloFolder& earlier : report.montecarlo) {
        if (earlier.label == mc.label) {
          io::fail_file(dir, "a second Monte Carlo of " + mc.manifest.scenario_source +
                                 " (give each scenario once, the consistency test first)");
        }
      }
    }
    report.montecarlo.push_back(std::move(mc));
  }
  for (const std::string& dir : options.sweep_dirs) {
    report.sweeps.push_back({dir, io::read_sweep_csv((fs::path(dir) / "sweep.csv").string())});
  }
  const std::string markdown = results_markdown(report);

  // The figures go to a scratch sibling first, which then replaces <stem>/ whole.
  const fs::path figures = page.parent_path() / report.figures_dir_name;
  const fs::path scratch = page.parent_path() / ("." + report.figures_dir_name + ".partial-" +
                                                 std::to_string(::getpid()));
  std::error_code ec;
  fs::remove_all(scratch, ec);
  fs::create_directories(scratch, ec);  // and the page's folder
  if (ec) io::fail_file(scratch.string(), "cannot create: " + ec.message());
  ReportOutcome outcome;
  try {
    const auto copy_all = [&](const std::string& dir, const std::string& label,
                              const std::vector<std::string>& names) {
      for (const std::string& name : names) {
        copy_figure(fs::path(dir) / "figures" / name, scratch / (label + "_" + name));
        outcome.figures.push_back((figures / (label + "_" + name)).string());
      }
    };
    if (report.sim) copy_all(report.sim->dir, "sim", report.sim->figures);
    if (report.real) copy_all(report.real->dir, "real", report.real->figures);
    for (const MonteCarloFolder& mc : report.montecarlo) copy_all(mc.dir, mc.label, mc.figures);
  } catch (...) {
    fs::remove_all(scratch, ec);
    throw;
  }
  fs::remove_all(figures, ec);
  fs::rename(scratch, figures, ec);
  if (ec) io::fail_file(figures.string(), "cannot put the figures in place: " + ec.message());
  io::write_file_atomically(page.string(), [&](std::ostream& out) { out << markdown; });
  return outcome;
}

void add_report_command(CLI::App& app, CommandLine&) {
  auto options = std::make_shared<ReportOptions>();
  CLI::App* report = app.add_subcommand(
      "report",
      "Write the results page (Table I on simulated and real data, the Monte Carlo consistency "
      "table, the figures) from folders that run, plot and montecarlo filled");
  report
      ->add_option("OUT_MD", options->out_path,
                   "The Markdown page; its figures are copied into <stem>/ beside it")
      ->required();
  report->add_option("--sim", options->sim_dir,
                     "Folder of result directories on a simulated dataset, plotted");
  report->add_option("--real", options->real_dir,
                     "Folder of result directories on the real dataset, plotted");
  report->add_option("--montecarlo", options->montecarlo_dirs,
                     "Monte Carlo directory, plotted; repeat for further scenarios, the page's "
                     "consistency test first");
  report->add_option("--sweep", options->sweep_dirs,
                     "Sweep directory (msislab sweep): its sweep.csv as a table; repeatable");
  report->callback([options] {
    const ReportOutcome outcome = write_report(*options);
    std::cout << "wrote " << options->out_path << " and " << outcome.figures.size()
              << " figures beside it" << std::endl;
  });
}

}  // namespace msislab::app
