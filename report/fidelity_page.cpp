// The texts of `msislab fidelity`: the command line, fidelity.md and fidelity.json.
#include <cmath>
#include <filesystem>

#include "io/atomic_file.hpp"
#include "io/text_lines.hpp"
#include "report/fidelity_report.hpp"
#include "results/results.hpp"
#include "slam/beam_segmentation.hpp"

namespace msislab::report {

namespace fs = std::filesystem;

namespace {

std::string quoted(const std::string& word) {
  if (!word.empty() && word.find_first_of(" \t'\"$\\`*?;&|<>()") == std::string::npos) {
    return word;
  }
  std::string text = "'";
  for (const char ch : word) text += ch == '\'' ? std::string("'\\''") : std::string(1, ch);
  return text + "'";
}

std::string dataset_table(const FidelityReport& r) {
  const auto row = [](const std::string& what, const std::string& real, const std::string& sim) {
    return "| " + what + " | " + real + " | " + sim + " |\n";
  };
  const auto both = [&](const std::string& what, auto field) {
    return row(what, field(r.real), field(r.sim));
  };
  return "| | real | simulated |\n| --- | --- | --- |\n" +
         both("dataset", [](const FidelitySide& s) { return "`" + s.dir + "`"; }) +
         both("keyframes (revolutions)",
              [](const FidelitySide& s) {
                return std::to_string(s.beams.front().keyframe) + ".." +
                       std::to_string(s.beams.back().keyframe) + " (" +
                       std::to_string(s.stats.keyframes) + ")";
              }) +
         both("beams counted, of all beams",
              [](const FidelitySide& s) {
                return io::format_count(s.stats.beams) + " of " + io::format_count(s.beam_times);
              }) +
         both("beams with a detection",
              [](const FidelitySide& s) {
                return io::format_count(s.stats.beams - s.stats.empty_beams);
              }) +
         both("detected bins",
              [](const FidelitySide& s) {
                return io::format_count(s.stats.detected_ranges_m.size());
              }) +
         both("sonar setup",
              [](const FidelitySide& s) {
                return io::format_number(s.setup.range_m) + " m range, " +
                       io::format_number(s.setup.bin_m) + " m bins, " +
                       std::to_string(io::steps_per_revolution(s.setup)) + " steps per revolution";
              }) +
         both("revolution drawn",
              [](const FidelitySide& s) { return "keyframe " + std::to_string(s.revolution); });
}

std::string readings_rule(const SegmentationConfig& seg) {
  const std::string groups = " of bins with gaps of at most one bin";
  if (seg.max_ranges_per_beam == 1)
    return "one reading per beam, at the centre of its nearest group" + groups;
  return "readings at the centres of the nearest " + std::to_string(seg.max_ranges_per_beam) +
         " groups" + groups;
}

std::string definitions(const FidelityReport& r) {
  const SegmentationConfig seg;
  return "- **Counted beams**: every beam inside a keyframe (one revolution) of the detections "
         "file, from its first to its last keyframe, " +
         std::to_string(io::steps_per_revolution(r.real.setup)) +
         " beams each (360 deg over the step of `*_SETUP.log`). A beam with no detected bin is "
         "empty. Beams outside every keyframe (before the first, after the last) are not "
         "counted.\n"
         "- **Detected bins per beam**: the rows of the detections file of a beam, averaged over "
         "all counted beams, empty ones included; the p90 is over the same beams.\n"
         "- **Runs**: a run is a group of detected bins with no gap (bin = range / bin size, "
         "rounded); a gap of one missing bin or more starts a new run. Runs per beam are "
         "averaged over all counted beams, and beams with 2 or more runs are a share of them.\n"
         "- **First detected range**: the smallest detected range of a beam, over the beams with "
         "a detection. Quantiles interpolate linearly between order statistics (position "
         "(n - 1) p in the sorted sample).\n"
         "- **KS**: the two-sample Kolmogorov-Smirnov distance sup |F_real(x) - F_sim(x)| between "
         "the empirical distribution functions (0: the same sample, 1: disjoint samples), on the "
         "median row of the distribution it measures: the first ranges, and all detected "
         "ranges.\n"
         "- **Detected range by 10 m band**: the share of all detected bins, and the share of "
         "first ranges, in each band [0, 10), [10, 20), ... m (the last band includes the sonar "
         "range); above them the quantiles and the KS distance of all detected ranges.\n"
         "- **Echo extent by incidence**: how far an echo smears in range, against how obliquely "
         "its beam meets the surface. For every beam whose two neighbouring beam rows in its "
         "keyframe have detections, with first ranges r-, r+ within 3 m of its own r: the "
         "incidence atan(|r+ - r-| / (2 r step)) (step: the head's angle step), and the length of "
         "its nearest run of detected bins, (last - first + 1) bins. Median per 15 deg band, with "
         "the KS distance of the two samples. On a flat wall the length grows about as r x "
         "(the beam's width above the threshold) x tan(incidence) beyond the pulse's extent at "
         "normal incidence, so the rows measure the beam's effective width and the echo's "
         "tail.\n"
         "- **Points per scan after segmentation**: the readings the project's front end takes "
         "from the detections (`dataset::load_sonar_readings` on detections, default "
         "`SegmentationConfig`: " +
         to_string(seg.method) + ", bins under " + io::format_number(seg.min_range_m) +
         " m ignored, " + readings_rule(seg) +
         "), counted per keyframe; mean, p10 and p90 over the keyframes.\n"
         "- **Beams per revolution**: for every angle step (`angle_idx`) with a detection in two "
         "consecutive keyframes k and k + 1, the beam rows between its two beams and their time "
         "difference in `*_IS_timestamps.log` (the revolution period); the medians.\n"
         "- **Navigation** (when both datasets have `*_DVL.log` and `*_MTi.log`; "
         "`eval/navigation_statistics`, docs/simulator.md): DVL velocity noise from the first "
         "differences of consecutive bottom-lock samples (no dropout between) over sqrt(2), "
         "per vehicle axis, as a standard deviation and robustly (1.4826 MAD); the DVL rate and "
         "the share of its rows without bottom lock; heading noise from the second differences "
         "of the wrapped MRU heading over sqrt(6); the heading change over one revolution: the "
         "median |change| of the MRU heading over every 13.8 s along the log (how much the "
         "vehicle turns between two scans); dead-reckoning drift per 100 m: the project's "
         "dead-reckoning EKF restarted at the truth every 25 m of path, its position error 100 m "
         "of path later, mean and p90 over the windows (truth: GPS for real data, the "
         "simulation's for simulated data)." +
         std::string(r.navigation ? "" : " Not computed here: a dataset lacks those logs.") +
         "\n"
         "- **sim / real**: the simulated value over the real one (`-` when the real one is 0).\n";
}

std::string figures(const FidelityReport& r) {
  return "![First detected range and all detected bins, real against simulated]"
         "(figures/ranges.png)\n\n"
         "*Range histograms in 1 m bins, in percent of each sample per metre: left the first "
         "detected range of each beam, right every detected bin; real solid black, simulated "
         "dashed blue; the titles give the KS distances.*\n\n"
         "![One revolution of detections from each dataset](figures/revolution.png)\n\n"
         "*Keyframe " +
         std::to_string(r.real.revolution) + " of the real data (left) and keyframe " +
         std::to_string(r.sim.revolution) +
         " of the simulated data (right), each in its vehicle frame (x forward, y port) at each "
         "beam's own time, without motion compensation: every detected bin (light), the first "
         "range of each beam (dark), range rings every 10 m around the sonar head.*\n";
}

io::Json side_json(const FidelitySide& s) {
  return {{"dataset", io::absolute_path(s.dir)},
          {"first_keyframe", s.beams.front().keyframe},
          {"last_keyframe", s.beams.back().keyframe},
          {"beams", s.beam_times},
          {"beams_counted", s.stats.beams},
          {"beams_with_detection", s.stats.beams - s.stats.empty_beams},
          {"detected_bins", s.stats.detected_ranges_m.size()},
          {"revolution_drawn", s.revolution}};
}

}  // namespace

std::string fidelity_command_line(const FidelityOptions& o) {
  std::string line = "msislab fidelity " + quoted(o.real_dir) + " " + quoted(o.sim_dir);
  if (!o.out_dir.empty()) line += " --out " + quoted(o.out_dir);
  if (o.revolution_real) line += " --revolution-real " + std::to_string(*o.revolution_real);
  if (o.revolution_sim) line += " --revolution-sim " + std::to_string(*o.revolution_sim);
  return line;
}

std::string fidelity_page(const FidelityReport& r) {
  const auto name = [](const FidelitySide& s) {
    fs::path path = fs::absolute(s.dir).lexically_normal();
    if (path.filename().empty()) path = path.parent_path();
    return path.filename().string();
  };
  return "# Simulator fidelity: " + name(r.sim) + " against " + name(r.real) + "\n\n" +
         "Generated by `" + fidelity_command_line(r.options) +
         "`. Both datasets' detections (`*_detections.csv[.gz]`, with the beam times of "
         "`*_IS_timestamps.log`) go through the same code.\n\n" +
         dataset_table(r) + "\n## Statistics\n\n" + fidelity_markdown(r.table) +
         "\n## How each statistic is computed\n\n" + definitions(r) + "\n## Figures\n\n" +
         figures(r);
}

io::Json fidelity_json(const FidelityReport& r) {
  const io::SonarSetup& s = r.real.setup;
  return {{"command", fidelity_command_line(r.options)},
          {"real", side_json(r.real)},
          {"sim", side_json(r.sim)},
          {"setup",
           {{"range_m", s.range_m},
            {"bin_m", s.bin_m},
            {"step_rad", s.step_rad},
            {"beams_per_revolution", io::steps_per_revolution(s)}}},
          {"rows", fidelity_rows_json(r.table)}};
}

}  // namespace msislab::report
