// The method catalogue: the methods a command can run, made from the built-in ones and a methods
// file, and handed to what runs them.
#include "app/method_catalogue.hpp"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "io/input_error.hpp"
#include "report/method_styles.hpp"
#include "test_support.hpp"

namespace msislab::app {
namespace {

namespace fs = std::filesystem;

TEST(MethodCatalogue, TheBuiltInMethodsBuildTheirBackEnds) {
  const MethodCatalogue catalogue;
  const report::MethodStyles styles(catalogue.methods_file());
  EXPECT_EQ(catalogue.names(), (std::vector<std::string>{"robocentric", "worldcentric", "posegraph",
                                                         "deadreckoning", "integration"}));
  EXPECT_EQ(MethodCatalogue::builtin_names(), catalogue.names());
  for (const Method& m : catalogue.methods()) {
    EXPECT_EQ(m.kind == MethodKind::kTrajectorySlam, static_cast<bool>(m.make_slam)) << m.name;
    EXPECT_EQ(catalogue.find(m.name), &m);
    // Every method the catalogue runs is one the figures know by its own title.
    EXPECT_LT(styles.rank(m.name), styles.all().size()) << m.name;
  }
  const GaussianPose2 start;
  for (const char* name : {"robocentric", "worldcentric", "posegraph"}) {
    const auto slam = catalogue.at(name).make_slam(SlamConfig{}, start);
    ASSERT_NE(slam, nullptr) << name;
    EXPECT_EQ(slam->scans(), 0u);
    EXPECT_EQ(slam->online_poses().has_value(), std::string(name) == "posegraph");
  }
}

TEST(MethodCatalogue, AnUnknownMethodIsOneClearError) {
  const MethodCatalogue catalogue;
  EXPECT_EQ(catalogue.find("ekf"), nullptr);
  try {
    catalogue.at("ekf", "--methods");
    ADD_FAILURE() << "no InputError";
  } catch (const io::InputError& e) {
    EXPECT_EQ(std::string(e.what()),
              "--methods 'ekf': not available in this build (available: robocentric, "
              "worldcentric, posegraph, deadreckoning, integration)");
  }
}

TEST(MethodCatalogue, AMethodsFilesMethodsComeAfterTheBuiltInOnes) {
  const testing::TempDir tmp;
  const fs::path file = tmp.path() / "methods.yaml";
  std::ofstream(file) << "methods:\n"
                         "  - name: mine\n"
                         "    title: My SLAM\n"
                         "    command: [my_slam, '{dataset}', '{out}']\n"
                         "    time_limit_s: 60\n"
                         "    colour: '#123456'\n";
  const MethodCatalogue catalogue = MethodCatalogue::with_methods_file(file.string());
  ASSERT_EQ(catalogue.methods().size(), 6u);
  const Method& mine = catalogue.at("mine");
  EXPECT_EQ(mine.kind, MethodKind::kExternal);
  ASSERT_TRUE(mine.external.has_value());
  EXPECT_EQ(mine.external->command.front(), "my_slam");
  const report::MethodStyles styles(catalogue.methods_file());
  EXPECT_EQ(styles.title("mine"), "My SLAM");
  EXPECT_EQ(styles.colour("mine"), 0x123456u);
  // A value: the catalogue made without the file does not know the method.
  EXPECT_EQ(MethodCatalogue().find("mine"), nullptr);
  EXPECT_EQ(MethodCatalogue::with_methods_file("").names(), MethodCatalogue().names());
}

}  // namespace
}  // namespace msislab::app
