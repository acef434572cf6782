// The SLAM config's footprint section (settings/footprint_yaml.hpp): what `msislab footprint`
// writes reads back as the same table (cells under min_samples as none), the line keys alone
// leave the table off, and bad tables are one InputError naming the file, line and key.
#include "settings/footprint_yaml.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "io/input_error.hpp"
#include "settings/config_yaml.hpp"
#include "test_support.hpp"

namespace msislab::settings {
namespace {

constexpr double kDegree = M_PI / 180.0;

FootprintEstimate two_by_three() {
  FootprintEstimate e;
  e.table.ranges_m = {10.0, 20.0};
  e.table.incidences_rad = {0.0, 30.0 * kDegree, 60.0 * kDegree};
  e.table.offset_m = {0.35, 0.41, NAN, 0.33, 0.5, -0.12345};
  e.table.sd_m = {0.15, 0.2, NAN, 0.3, 0.45, 0.9};
  e.samples = {120, 40, 3, 80, 25, 19};
  return e;
}

TEST(FootprintYaml, WhatIsWrittenReadsBackAsTheSameTable) {
  LineNormalConfig line{2.5, 4, 0.04};
  const std::string text = "trajectory_slam: {iekf_iterations: 3}\n" +
                           footprint_section_yaml(two_by_three(), 20, line, "two lines\nof note");
  EXPECT_EQ(text.find("# two lines\n# of note\nfootprint:\n"), text.find("# two lines"));
  const SlamConfig config = read_slam_config_text(text, "written.yaml");
  const FootprintTable& t = config.footprint.table;
  EXPECT_EQ(config.trajectory_slam.front_end.iekf_iterations, 3);
  ASSERT_EQ(t.ranges_m, two_by_three().table.ranges_m);
  ASSERT_EQ(t.incidences_rad.size(), 3u);
  EXPECT_NEAR(t.incidences_rad[2], 60.0 * kDegree, 1e-12);
  const FootprintTable& in = two_by_three().table;
  for (std::size_t c = 0; c < 6; ++c) {
    // 20 samples or more: the figure to the 4 decimals written; fewer (3, 19): none.
    if (c == 2 || c == 5) {
      EXPECT_TRUE(std::isnan(t.offset_m[c]) && std::isnan(t.sd_m[c])) << c;
    } else {
      EXPECT_NEAR(t.offset_m[c], in.offset_m[c], 5e-5) << c;
      EXPECT_NEAR(t.sd_m[c], in.sd_m[c], 5e-5) << c;
    }
  }
  EXPECT_EQ(config.footprint.line.radius_m, 2.5);
  EXPECT_EQ(config.footprint.line.min_points, 4);
  EXPECT_EQ(config.footprint.line.max_eigen_ratio, 0.04);
  // Without the section, or with its line keys alone: no table.
  EXPECT_TRUE(read_slam_config_text("footprint: {line_radius_m: 2}\n", "lines.yaml")
                  .footprint.table.empty());
  EXPECT_TRUE(read_slam_config_text("{}\n", "empty.yaml").footprint.table.empty());
}

void expect_bad_footprint(const std::string& section, int line, const std::string& key) {
  const testing::TempDir dir;
  const std::string path = testing::write_text(dir.file("slam.yaml"), "footprint:\n" + section);
  try {
    read_slam_config(path);
    ADD_FAILURE() << "no InputError for\n" << section;
  } catch (const io::InputError& e) {
    const std::string message = e.what();
    EXPECT_NE(message.find(path + ":" + std::to_string(line) + ":"), std::string::npos)
        << message << "\nexpected line " << line;
    EXPECT_NE(message.find("key '" + key + "'"), std::string::npos) << message;
  }
}

TEST(FootprintYaml, BadTablesAreRefused) {
  const std::string row = "    - {offset_m: [0.3, 0.4], sd_m: [0.1, 0.2], samples: [30, 30]}\n";
  const std::string rows = "  rows:\n" + row + row;
  // Lines count from 1; line 1 is "footprint:".
  expect_bad_footprint(
      "  ranges_m: [20, 10]\n  incidences_deg: [0, 45]\n  min_samples: 20\n" + rows, 2,
      "footprint.ranges_m");
  expect_bad_footprint(
      "  ranges_m: [10, 20]\n  incidences_deg: [0, 95]\n  min_samples: 20\n" + rows, 3,
      "footprint.incidences_deg");
  expect_bad_footprint("  ranges_m: [10, 20]\n  incidences_deg: [0, 45]\n  min_samples: 1\n" + rows,
                       4, "footprint.min_samples");
  expect_bad_footprint(
      "  ranges_m: [10, 20]\n  incidences_deg: [0, 45]\n  min_samples: 20\n"
      "  rows:\n" +
          row,
      6, "footprint.rows");  // the rows' first line
  expect_bad_footprint(
      "  ranges_m: [10, 20]\n  incidences_deg: [0, 45]\n  min_samples: 20\n  rows:\n" + row +
          "    - {offset_m: [0.3], sd_m: [0.1, 0.2], samples: [30, 30]}\n",
      7, "footprint.rows[1].offset_m");
  expect_bad_footprint(
      "  ranges_m: [10, 20]\n  incidences_deg: [0, 45]\n  min_samples: 20\n  rows:\n" + row +
          "    - {offset_m: [0.3, 0.4], sd_m: [0.1, -0.2], samples: [30, 30]}\n",
      7, "footprint.rows[1].sd_m");
  expect_bad_footprint(
      "  ranges_m: [10, 20]\n  incidences_deg: [0, 45]\n  min_samples: 20\n  rows:\n" + row +
          "    - {offset_m: [0.3, 0.4], sd_m: [0.1, 0.2], samples: [30, 2.5]}\n",
      7, "footprint.rows[1].samples");
  expect_bad_footprint(
      "  ranges_m: [10, 20]\n  incidences_deg: [0, 45]\n  min_samples: 20\n  rows:\n" + row +
          "    - {offset_m: [0.3, .nan], sd_m: [0.1, 0.2], samples: [30, 30]}\n",
      7, "footprint.rows[1].offset_m");
  expect_bad_footprint("  ranges_m: [10, 20]\n" + rows, 1, "footprint.incidences_deg");
  expect_bad_footprint("  line_radius_m: 3\n  line_radious: 2\n", 3, "footprint.line_radious");
}

}  // namespace
}  // namespace msislab::settings
