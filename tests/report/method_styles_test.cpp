// The methods' styles: a name, title, colour and line style for each method figures and tables
// show, the built-in ones' and a methods file's.
#include "report/method_styles.hpp"

#include <gtest/gtest.h>

#include <set>

namespace msislab::report {
namespace {

TEST(MethodStyles, EveryBuiltInMethodHasADistinctNameTitleAndColour) {
  const MethodStyles styles;
  std::set<std::string> names, titles;
  std::set<std::uint32_t> colours;
  std::vector<std::string> in_order;
  for (const MethodStyle& s : styles.all()) {
    EXPECT_TRUE(names.insert(s.name).second) << s.name;
    EXPECT_TRUE(titles.insert(s.title).second) << s.title;
    EXPECT_TRUE(colours.insert(s.colour).second) << s.name;
    in_order.push_back(s.name);
  }
  EXPECT_EQ(in_order, (std::vector<std::string>{"robocentric", "worldcentric", "posegraph",
                                                "deadreckoning", "integration"}));
  EXPECT_EQ(styles.line("worldcentric"), plot::SeriesStyle::kDashedLine);
  EXPECT_LT(styles.rank("robocentric"), styles.rank("deadreckoning"));
}

TEST(MethodStyles, AnUnknownMethodIsShownUnderItsName) {
  // A result of a method these styles do not know still plots and tabulates.
  const MethodStyles styles;
  EXPECT_EQ(styles.title("ekf"), "ekf");
  EXPECT_EQ(styles.colour("ekf"), name_colour("ekf"));
  EXPECT_EQ(styles.line("ekf"), plot::SeriesStyle::kLine);
  EXPECT_EQ(styles.rank("ekf"), styles.all().size());
}

TEST(MethodStyles, AMethodsFilesMethodsComeAfterTheBuiltInOnesWithTheirStyles) {
  settings::MethodsFile file;
  settings::ExternalMethod mine;
  mine.name = "mine";
  mine.title = "My SLAM";
  mine.colour = 0x123456;
  mine.line_style = "dotted";
  settings::ExternalMethod plain;
  plain.name = "plain";
  plain.title = "Plain";
  file.methods = {mine, plain};
  const MethodStyles styles(file);
  ASSERT_EQ(styles.all().size(), 7u);
  EXPECT_EQ(styles.rank("mine"), 5u);
  EXPECT_EQ(styles.title("mine"), "My SLAM");
  EXPECT_EQ(styles.colour("mine"), 0x123456u);
  EXPECT_EQ(styles.line("mine"), plot::SeriesStyle::kDottedLine);
  EXPECT_EQ(styles.colour("plain"), name_colour("plain"));  // no colour given
  EXPECT_EQ(styles.line("plain"), plot::SeriesStyle::kLine);
  EXPECT_EQ(styles.title("robocentric"), MethodStyles().title("robocentric"));
}

}  // namespace
}  // namespace msislab::report
