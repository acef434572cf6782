#include "report/fidelity_table.hpp"

#include <algorithm>
#include <cmath>

#include "io/text_lines.hpp"
#include "results/results.hpp"
#include "stats/sample_statistics.hpp"

namespace msislab::report {

namespace {

constexpr double kBand_m = 10.0;

double percent_of(std::size_t part, std::size_t whole) {
  return whole == 0 ? std::numeric_limits<double>::quiet_NaN()
                    : 100.0 * static_cast<double>(part) / static_cast<double>(whole);
}

std::size_t count_at_least(const std::vector<double>& values, double least) {
  std::size_t n = 0;
  for (const double v : values) n += v >= least;
  return n;
}

/// p10, median (with the KS distance of the two samples) and p90 of one distribution.
void add_quantiles(FidelityTable& table, const std::string& section, const std::string& key,
                   const std::string& name, const std::vector<double>& real,
                   const std::vector<double>& sim, const std::string& unit, int decimals) {
  table.push_back({section, key + "_p10" + (unit.empty() ? "" : "_" + unit), name + ", p10",
                   quantile(real, 0.1), quantile(sim, 0.1), std::nullopt, unit, decimals});
  table.push_back({section, key + "_median" + (unit.empty() ? "" : "_" + unit), name + ", median",
                   quantile(real, 0.5), quantile(sim, 0.5), ks_distance(real, sim), unit,
                   decimals});
  table.push_back({section, key + "_p90" + (unit.empty() ? "" : "_" + unit), name + ", p90",
                   quantile(real, 0.9), quantile(sim, 0.9), std::nullopt, unit, decimals});
}

void add_per_beam(FidelityTable& t, const SonarStatistics& real, const SonarStatistics& sim) {
  const std::string s = "Per beam";
  t.push_back({s, "empty_beams_percent", "beams with no detection",
               percent_of(real.empty_beams, real.beams), percent_of(sim.empty_beams, sim.beams),
               std::nullopt, "%", 1});
  t.push_back({s, "bins_per_beam_mean", "detected bins per beam, mean", mean(real.bins_per_beam),
               mean(sim.bins_per_beam), std::nullopt, "", 2});
  t.push_back({s, "bins_per_beam_p90", "detected bins per beam, p90",
               quantile(real.bins_per_beam, 0.9), quantile(sim.bins_per_beam, 0.9), std::nullopt,
               "", 1});
  t.push_back({s, "runs_per_beam_mean", "runs of consecutive bins per beam, mean",
               mean(real.runs_per_beam), mean(sim.runs_per_beam), std::nullopt, "", 3});
  t.push_back({s, "multi_run_beams_percent", "beams with 2 or more runs",
               percent_of(count_at_least(real.runs_per_beam, 2.0), real.beams),
               percent_of(count_at_least(sim.runs_per_beam, 2.0), sim.beams), std::nullopt, "%",
               2});
  add_quantiles(t, s, "first_range", "first detected range", real.first_ranges_m,
                sim.first_ranges_m, "m", 2);
}

void add_bands(FidelityTable& t, const SonarStatistics& real, const SonarStatistics& sim,
               double max_range_m) {
  const std::string s = "Detected range by 10 m band";
  add_quantiles(t, s, "detected_range", "detected range (all bins)", real.detected_ranges_m,
                sim.detected_ranges_m, "m", 2);
  const int bands = std::max(1, static_cast<int>(std::ceil(max_range_m / kBand_m - 1e-9)));
  const auto add_shares = [&](const std::string& key, const std::string& name,
                              const std::vector<double>& r, const std::vector<double>& m) {
    const std::vector<double> real_shares = band_shares(r, kBand_m, bands);
    const std::vector<double> sim_shares = band_shares(m, kBand_m, bands);
    for (int k = 0; k < bands; ++k) {
      const std::string band = std::to_string(10 * k) + "-" + std::to_string(10 * (k + 1));
      t.push_back(
          {s,
           key + "_" + std::to_string(10 * k) + "_" + std::to_string(10 * (k + 1)) + "_m_percent",
           name + " at " + band + " m", 100.0 * real_shares[k], 100.0 * sim_shares[k], std::nullopt,
           "%", 1});
    }
  };
  add_shares("detected_bins", "detected bins", real.detected_ranges_m, sim.detected_ranges_m);
  add_shares("first_ranges", "first ranges", real.first_ranges_m, sim.first_ranges_m);
}

void add_run_lengths(FidelityTable& t, const SonarStatistics& real, const SonarStatistics& sim) {
  const std::string s = "Echo extent by incidence";
  for (int k = 0; k < kIncidenceBands; ++k) {
    const auto band = static_cast<std::size_t>(k);
    const auto lo = static_cast<int>(k * kIncidenceBand_deg);
    const auto hi = static_cast<int>((k + 1) * kIncidenceBand_deg);
    const std::vector<double>& r = real.run_length_by_incidence_m.at(band);
    const std::vector<double>& m = sim.run_length_by_incidence_m.at(band);
    t.push_back({s,
                 "first_run_length_incidence_" + std::to_string(lo) + "_" + std::to_string(hi) +
                     "_deg_median_m",
                 "nearest run's length at incidence " + std::to_string(lo) + "-" +
                     std::to_string(hi) + " deg, median",
                 quantile(r, 0.5), quantile(m, 0.5),
                 r.empty() || m.empty() ? std::nullopt : std::optional<double>(ks_distance(r, m)),
                 "m", 2});
  }
}

void add_scans_and_rotation(FidelityTable& t, const SonarStatistics& real,
                            const SonarStatistics& sim) {
  const std::string scans = "Scans after segmentation";
  t.push_back({scans, "points_per_scan_mean", "points per scan, mean",
               mean(real.readings_per_revolution), mean(sim.readings_per_revolution), std::nullopt,
               "", 1});
  t.push_back({scans, "points_per_scan_p10", "points per scan, p10",
               quantile(real.readings_per_revolution, 0.1),
               quantile(sim.readings_per_revolution, 0.1), std::nullopt, "", 1});
  t.push_back({scans, "points_per_scan_p90", "points per scan, p90",
               quantile(real.readings_per_revolution, 0.9),
               quantile(sim.readings_per_revolution, 0.9), std::nullopt, "", 1});
  const std::string rotation = "Sonar rotation";
  t.push_back({rotation, "beams_per_revolution", "beams per 360 deg, median",
               quantile(real.beams_per_360, 0.5), quantile(sim.beams_per_360, 0.5), std::nullopt,
               "", 1});
  t.push_back({rotation, "revolution_period_s", "revolution period, median",
               quantile(real.revolution_period_s, 0.5), quantile(sim.revolution_period_s, 0.5),
               std::nullopt, "s", 2});
}

std::string cell(double value, int decimals) {
  return std::isfinite(value) ? io::format_fixed(value, decimals) : "-";
}

}  // namespace

double ratio(const FidelityRow& row) {
  if (!std::isfinite(row.real) || !std::isfinite(row.sim) || row.real == 0.0) {
    return std::numeric_limits<double>::quiet_NaN();
  }
  return row.sim / row.real;
}

FidelityTable sonar_rows(const SonarStatistics& real, const SonarStatistics& sim,
                         double max_range_m) {
  FidelityTable table;
  add_per_beam(table, real, sim);
  add_bands(table, real, sim, max_range_m);
  add_run_lengths(table, real, sim);
  add_scans_and_rotation(table, real, sim);
  return table;
}

std::string fidelity_markdown(const FidelityTable& table) {
  std::string text =
      "| statistic | real | simulated | sim / real | KS |\n"
      "| --- | ---: | ---: | ---: | ---: |\n";
  std::string section;
  for (const FidelityRow& row : table) {
    if (row.section != section) {
      section = row.section;
      text += "| **" + section + "** | | | | |\n";
    }
    text += "| " + row.name + (row.unit.empty() ? "" : " (" + row.unit + ")") + " | " +
            cell(row.real, row.decimals) + " | " + cell(row.sim, row.decimals) + " | " +
            cell(ratio(row), 2) + " | " + (row.ks ? cell(*row.ks, 3) : "") + " |\n";
  }
  return text;
}

io::Json fidelity_rows_json(const FidelityTable& table) {
  io::Json rows = io::Json::array();
  for (const FidelityRow& r : table) {
    rows.push_back({{"section", r.section},
                    {"key", r.key},
                    {"name", r.name},
                    {"unit", r.unit},
                    {"real", r.real},
                    {"sim", r.sim},
                    {"ratio", ratio(r)},
                    {"ks", r.ks ? io::Json(*r.ks) : io::Json()}});
  }
  return rows;
}

}  // namespace msislab::report
