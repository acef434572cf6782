#include <algorithm>
#include <cmath>
#include <filesystem>

#include "io/text_lines.hpp"
#include "report/method_styles.hpp"
#include "report/results_markdown.hpp"
#include "stats/chi_square.hpp"

namespace msislab::report {

namespace fs = std::filesystem;

std::string fixed(double value, int decimals) {
  return std::isfinite(value) ? io::format_fixed(value, decimals) : "n/a";
}

std::string fixed(const std::optional<double>& value, int decimals) {
  return value ? fixed(*value, decimals) : "n/a";
}

std::string percent(const std::optional<double>& fraction) {
  return fraction ? fixed(100.0 * *fraction, 1) + " %" : "n/a";
}

namespace {

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

void table_one(const MethodStyles& styles, std::ostringstream& md, const ResultFolder& folder,
               const std::string& truth_name) {
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
    md << "| " << styles.title(m.method) << " | **" << fixed(m.errors.mean_m, 2) << "** |";
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
    md << "- " << styles.title(m.method) << ": " << fixed(smoothed->second, 2)
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
/// (the lettered ones (a)-(d) first, then the others); `truth` names the reference.
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

/// The Monte Carlo table: a row per method, its runs, mean error (overall and per segment), ANEES,
/// share of scan steps in the NEES bounds and run time.
void montecarlo_table(const MethodStyles& styles, std::ostringstream& md,
                      const MonteCarloFolder& mc) {
  const std::vector<std::string> segments = segment_names(
      mc.methods,
      [](const results::StoredSummary& s) -> const auto& { return s.summary.segments; });
  md << "| method | runs | failed | mean error [m] |";
  for (const std::string& s : segments) md << " " << s << " [m] |";
  md << " ANEES | scan steps with NEES in the 95% bounds | bounds | run time per run [s] |\n"
     << "| --- | ---: | ---: | ---: |";
  for (std::size_t i = 0; i < segments.size(); ++i) md << " ---: |";
  md << " ---: | ---: | --- | ---: |\n";
  for (const results::StoredSummary& stored : mc.methods) {
    const MethodSummary& s = stored.summary;
    md << "| " << styles.title(s.method) << " | " << s.runs << " | " << s.failed << " | "
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
}

/// Robocentric against world-centric consistency, when both are in the folder.
void robocentric_verdict(std::ostringstream& md, const MonteCarloFolder& mc) {
  const MethodSummary* rc = nullptr;
  const MethodSummary* wc = nullptr;
  for (const results::StoredSummary& stored : mc.methods) {
    const MethodSummary& s = stored.summary;
    if (s.method == "robocentric") rc = &s;
    if (s.method == "worldcentric") wc = &s;
  }
  if (!rc || !wc || !rc->anees || !wc->anees || !rc->nees_in_bounds_fraction ||
      !wc->nees_in_bounds_fraction) {
    return;
  }
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

/// A Monte Carlo folder's section; `first`: the page's consistency test, else titled by its
/// scenario.
void montecarlo_section(const MethodStyles& styles, std::ostringstream& md,
                        const MonteCarloFolder& mc, const std::string& figures_dir, bool first) {
  const results::MonteCarloManifest& m = mc.manifest;
  const std::string scenario = fs::path(m.scenario_source).filename().string();
  md << "\n## Monte Carlo consistency" << (first ? "" : ": `" + scenario + "`") << "\n\n"
     << m.runs << " seeded runs of the scenario `" << scenario << "` (seeds " << m.first_seed
     << " to " << m.first_seed + static_cast<std::uint64_t>(m.runs) - 1
     << "), each simulated and run by every method; `" << mc.dir << "`.\n\n";
  montecarlo_table(styles, md, mc);
  md << "\nThe NEES of the 3-DOF scan pose is averaged over the runs at each scan step; N runs "
        "times that average is chi-square with 3N degrees of freedom for a consistent filter, so "
        "the two-sided 95% bounds apply to each step (docs/trajectory_slam.md). The ANEES averages "
        "it over the steps too.\n";
  robocentric_verdict(md, mc);
  figure_list(md, figures_dir, mc.label, "truth", mc.figures);
}

/// True when the page reports on the St. Pere data: the real run, or the shipped replica of it.
bool about_stpere(const ResultsReport& report) {
  return report.real || (report.sim && report.sim->scenario == "stpere_replica");
}

void introduction(std::ostringstream& md, const ResultsReport& report) {
  md << "# Results\n\n"
        "Generated by `msislab report` from the result folders named below; do not edit it by "
        "hand.";
  if (!about_stpere(report)) {
    md << "\n";
    return;
  }
  md << " `tools/results.sh` regenerates docs/results.md (every method on the simulated St. "
        "Pere replica and on the real St. Pere dataset, the Monte Carlo consistency test on the "
        "replica and on the failure scenarios, the figures); `tools/main.sh` writes the same page "
        "without the Monte Carlo as "
        "out/results.md. The paper (Burguera, Gonzalez, Oliver) reports on the real data a "
        "mean error of **1.15 m** for the robocentric and **2.05 m** for the world-centric "
        "trajectory (its Table I). Why the two filters agree here: docs/trajectory_slam.md; "
        "whether they differ in any regime (heading and DVL noise, revolution period, EKF "
        "against IEKF, compass, loop length, 20 paired runs a cell): docs/robocentric.md, whose "
        "sweeps close this page when tools/robocentric_study.sh has filled out/study.\n";
}

/// "the simulated St. Pere replica" for the shipped replica, else "the simulated dataset `NAME`".
std::string simulated_title(const ResultFolder& sim) {
  if (sim.scenario == "stpere_replica") return "Table I on the simulated St. Pere replica";
  return "Table I on the simulated dataset `" + sim.scenario + "`";
}

}  // namespace

std::string results_markdown(const ResultsReport& report) {
  std::ostringstream md;
  introduction(md, report);
  const auto section = [&](const ResultFolder& folder, const std::string& title,
                           const std::string& truth_name) {
    md << "\n## " << title << "\n\n";
    md << "Results in `" << folder.dir << "`";
    if (!folder.dataset.empty()) {
      md << ", dataset `" << fs::path(folder.dataset).filename().string() << "`";
    }
    md << ".\n\n";
    table_one(report.styles, md, folder, truth_name);
    figure_list(md, report.figures_dir_name, folder.label, truth_name, folder.figures);
  };
  if (report.sim) section(*report.sim, simulated_title(*report.sim), "simulation truth");
  if (report.real) {
    section(*report.real, "Table I on the real St. Pere dataset", "GPS track");
    md << "\nThe paper on the same data: robocentric 1.15 m, world-centric 2.05 m mean error.\n";
  }
  for (std::size_t i = 0; i < report.montecarlo.size(); ++i) {
    montecarlo_section(report.styles, md, report.montecarlo[i], report.figures_dir_name, i == 0);
  }
  if (!report.sensitivity.empty()) {
    sensitivity_section(report.styles, md, report.sensitivity_source, report.sensitivity);
  }
  for (const SweepFolder& sweep : report.sweeps) sweep_section(report.styles, md, sweep);
  return md.str();
}

}  // namespace msislab::report
