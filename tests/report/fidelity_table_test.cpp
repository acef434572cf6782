// The fidelity table: ratios, the sonar rows of two hand-made statistics, a row appended later
// (as the navigation rows will be), and the Markdown and JSON renderings (the JSON read back by
// the project's strict reader).
#include "report/fidelity_table.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>

#include "io/json.hpp"

namespace msislab::report {
namespace {

const FidelityRow& find_row(const FidelityTable& table, const std::string& key) {
  const auto it =
      std::find_if(table.begin(), table.end(), [&](const FidelityRow& r) { return r.key == key; });
  if (it == table.end()) throw std::runtime_error("no row " + key);
  return *it;
}

/// 4 counted beams, 2 empty: bins {3, 1, 0, 0}, runs {2, 1, 0, 0}.
SonarStatistics small_statistics(double shift_m) {
  SonarStatistics s;
  s.keyframes = 1;
  s.beams = 4;
  s.empty_beams = 2;
  s.bins_per_beam = {3, 1, 0, 0};
  s.runs_per_beam = {2, 1, 0, 0};
  s.first_ranges_m = {12.0 + shift_m, 31.0 + shift_m};
  s.detected_ranges_m = {12.0 + shift_m, 12.1 + shift_m, 14.0 + shift_m, 31.0 + shift_m};
  s.beams_per_360 = {200.0};
  s.revolution_period_s = {13.8};
  s.readings_per_revolution = {2.0};
  s.run_length_by_incidence_m = {{1.0 + shift_m, 2.0 + shift_m, 3.0 + shift_m}, {}, {}, {}, {5.0}};
  return s;
}

TEST(FidelityRow, RatioIsSimOverReal) {
  FidelityRow row{"s", "k", "n", 2.0, 3.0, std::nullopt, "", 2};
  EXPECT_DOUBLE_EQ(ratio(row), 1.5);
  row.real = 0.0;
  EXPECT_TRUE(std::isnan(ratio(row)));
  row.real = std::nan("");
  EXPECT_TRUE(std::isnan(ratio(row)));
}

TEST(SonarRows, ComputeEachStatisticFromTheSamples) {
  const FidelityTable table = sonar_rows(small_statistics(0.0), small_statistics(1.0), 50.0);
  EXPECT_DOUBLE_EQ(find_row(table, "empty_beams_percent").real, 50.0);
  EXPECT_DOUBLE_EQ(find_row(table, "bins_per_beam_mean").real, 1.0);
  EXPECT_DOUBLE_EQ(find_row(table, "runs_per_beam_mean").real, 0.75);
  EXPECT_DOUBLE_EQ(find_row(table, "multi_run_beams_percent").real, 25.0);
  const FidelityRow& median = find_row(table, "first_range_median_m");
  EXPECT_DOUBLE_EQ(median.real, 21.5);
  EXPECT_DOUBLE_EQ(median.sim, 22.5);
  ASSERT_TRUE(median.ks.has_value());
  EXPECT_DOUBLE_EQ(*median.ks, 0.5);  // {12, 31} against {13, 32}
  EXPECT_FALSE(find_row(table, "first_range_p10_m").ks.has_value());
  EXPECT_DOUBLE_EQ(find_row(table, "detected_bins_10_20_m_percent").real, 75.0);
  EXPECT_DOUBLE_EQ(find_row(table, "detected_bins_30_40_m_percent").sim, 25.0);
  EXPECT_DOUBLE_EQ(find_row(table, "first_ranges_10_20_m_percent").real, 50.0);
  EXPECT_NO_THROW(find_row(table, "first_ranges_40_50_m_percent"));
  EXPECT_THROW(find_row(table, "first_ranges_50_60_m_percent"), std::runtime_error);
  EXPECT_DOUBLE_EQ(find_row(table, "points_per_scan_mean").real, 2.0);
  const FidelityRow& normal = find_row(table, "first_run_length_incidence_0_15_deg_median_m");
  EXPECT_DOUBLE_EQ(normal.real, 2.0);
  EXPECT_DOUBLE_EQ(normal.sim, 3.0);
  ASSERT_TRUE(normal.ks.has_value());
  EXPECT_NEAR(*normal.ks, 1.0 / 3.0, 1e-12);  // {1, 2, 3} against {2, 3, 4}
  EXPECT_TRUE(std::isnan(find_row(table, "first_run_length_incidence_15_30_deg_median_m").real));
  EXPECT_DOUBLE_EQ(find_row(table, "first_run_length_incidence_60_75_deg_median_m").sim, 5.0);
  EXPECT_DOUBLE_EQ(find_row(table, "beams_per_revolution").real, 200.0);
  EXPECT_DOUBLE_EQ(find_row(table, "revolution_period_s").sim, 13.8);
}

TEST(SonarRows, BandsFollowTheSonarRange) {
  const FidelityTable table = sonar_rows(small_statistics(0.0), small_statistics(0.0), 30.0);
  EXPECT_NO_THROW(find_row(table, "detected_bins_20_30_m_percent"));
  EXPECT_THROW(find_row(table, "detected_bins_30_40_m_percent"), std::runtime_error);
}

TEST(FidelityMarkdown, OneLinePerRowUnderItsSection) {
  FidelityTable table = sonar_rows(small_statistics(0.0), small_statistics(0.0), 50.0);
  table.push_back(
      {"Navigation", "dvl_noise_mps", "DVL velocity noise", 0.2, 0.1, std::nullopt, "m/s", 3});
  const std::string md = fidelity_markdown(table);
  EXPECT_EQ(md.rfind("| statistic | real | simulated | sim / real | KS |\n", 0), 0u) << md;
  EXPECT_NE(md.find("| **Per beam** | | | | |\n| beams with no detection (%) | 50.0 | 50.0 | "
                    "1.00 |  |\n"),
            std::string::npos)
      << md;
  EXPECT_NE(md.find("| first detected range, median (m) | 21.50 | 21.50 | 1.00 | 0.000 |"),
            std::string::npos)
      << md;
  EXPECT_NE(md.find("| **Navigation** | | | | |\n| DVL velocity noise (m/s) | 0.200 | 0.100 | "
                    "0.50 |  |\n"),
            std::string::npos)
      << md;
  table.back().real = std::nan("");
  EXPECT_NE(fidelity_markdown(table).find("| DVL velocity noise (m/s) | - | 0.100 | - |  |"),
            std::string::npos);
}

TEST(FidelityRowsJson, EveryRowReadsBack) {
  FidelityTable table = sonar_rows(small_statistics(0.0), small_statistics(1.0), 50.0);
  table.front().real = 0.0;  // ratio undefined
  const io::Json rows =
      io::parse_json(io::format_json(fidelity_rows_json(table), {0, {}}), "rows.json");
  ASSERT_TRUE(rows.is_array());
  ASSERT_EQ(rows.size(), table.size());
  for (std::size_t i = 0; i < table.size(); ++i) {
    const io::JsonObject row(rows[i], "rows.json");
    EXPECT_EQ(row.string("key"), table[i].key);
    EXPECT_EQ(row.string("section"), table[i].section);
    EXPECT_EQ(row.string("unit"), table[i].unit);
    EXPECT_EQ(row.number_or_null("ks"), table[i].ks);
  }
  const io::JsonObject first(rows[0], "rows.json");
  EXPECT_EQ(first.number_or_null("ratio"), std::nullopt);
  const io::JsonObject median(rows[6], "rows.json");
  EXPECT_EQ(median.string("key"), "first_range_median_m");
  EXPECT_DOUBLE_EQ(median.number("real"), 21.5);
  EXPECT_DOUBLE_EQ(median.number("ratio"), 22.5 / 21.5);
  EXPECT_EQ(io::parse_json(io::format_json(fidelity_rows_json({})), "empty.json").size(), 0u);
}

}  // namespace
}  // namespace msislab::report
