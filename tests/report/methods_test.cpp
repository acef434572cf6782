// The method registry: one entry per method, what run, montecarlo, plot and report read of it.
#include "report/methods.hpp"

#include <gtest/gtest.h>

#include <set>

#include "io/input_error.hpp"

namespace msislab::report {
namespace {

TEST(Methods, EveryMethodHasADistinctNameTitleAndColour) {
  std::set<std::string> names, titles;
  std::set<std::uint32_t> colours;
  for (const MethodInfo& m : methods()) {
    EXPECT_TRUE(names.insert(m.name).second) << m.name;
    EXPECT_TRUE(titles.insert(m.title).second) << m.title;
    EXPECT_TRUE(colours.insert(m.colour).second) << m.name;
    EXPECT_EQ(m.kind == MethodKind::kTrajectorySlam, static_cast<bool>(m.make_slam)) << m.name;
    EXPECT_EQ(find_method(m.name), &m);
  }
  EXPECT_EQ(method_names(), (std::vector<std::string>{"robocentric", "worldcentric", "posegraph",
                                                      "deadreckoning", "integration"}));
  // The registry builds each back end: the two filters and the pose graph.
  const GaussianPose2 start;
  for (const char* name : {"robocentric", "worldcentric", "posegraph"}) {
    const auto slam = method_info(name).make_slam(SlamConfig{}, start);
    ASSERT_NE(slam, nullptr) << name;
    EXPECT_EQ(slam->scans(), 0u);
    EXPECT_EQ(slam->online_poses().has_value(), std::string(name) == "posegraph");
  }
}

TEST(Methods, AnUnknownMethodIsOneClearErrorOrShownAsNamed) {
  try {
    method_info("ekf", "--methods");
    ADD_FAILURE() << "no InputError";
  } catch (const io::InputError& e) {
    EXPECT_EQ(std::string(e.what()),
              "--methods 'ekf': not available in this build (available: robocentric, "
              "worldcentric, posegraph, deadreckoning, integration)");
  }
  EXPECT_EQ(find_method("ekf"), nullptr);
  // A result of a method this build does not know still plots and tabulates.
  EXPECT_EQ(method_title("ekf"), "ekf");
  EXPECT_EQ(method_colour("ekf"), method_colour("ekf"));
  EXPECT_EQ(method_style("ekf"), plot::SeriesStyle::kLine);
  EXPECT_EQ(method_rank("ekf"), methods().size());
  EXPECT_LT(method_rank("robocentric"), method_rank("deadreckoning"));
  EXPECT_EQ(method_style("worldcentric"), plot::SeriesStyle::kDashedLine);
}

}  // namespace
}  // namespace msislab::report
