// A keyframe of a dataset's detections read as a revolution (io/sonar_revolution; `msislab image
// --keyframe K` draws it like a raw one): its detected bins at full intensity and the rest 0, so
// the real data (detections only) and a simulated dataset can be looked at side by side; a
// keyframe the file does not hold is one clear error.
#include "dataset/sonar_revolution.hpp"

#include <gtest/gtest.h>

#include <cstdint>
#include <string>
#include <vector>

#include "io/detections.hpp"
#include "io/input_error.hpp"
#include "io/stpere_logs.hpp"
#include "test_support.hpp"

namespace msislab::dataset {
namespace {

using testing::TempDir;

/// Two keyframes: keyframe 1 with two beams (bins at 2.0 and 2.1 m on the first, 3.0 m on the
/// second), keyframe 2 with one beam at 4.0 m.
std::string detections_dataset(const TempDir& tmp) {
  io::write_setup_log(tmp.file("x_SETUP.log"), io::SonarSetup{});
  const double step = io::SonarSetup{}.step_rad;
  io::write_detections(tmp.file("x_detections.csv"), {{1, 10, 100.0, 1, 199, 199 * step, 2.0},
                                                      {1, 10, 100.0, 1, 199, 199 * step, 2.1},
                                                      {1, 11, 100.1, 2, 198, 198 * step, 3.0},
                                                      {2, 210, 114.0, 3, 199, 199 * step, 4.0}});
  return tmp.path().string();
}

TEST(DetectedRevolution, AKeyframeOfDetectionsBecomesBeamsOfFullIntensity) {
  const TempDir tmp;
  const SonarRevolution one = read_detected_revolution(detections_dataset(tmp), 1);
  ASSERT_EQ(one.beams.size(), 2u);
  EXPECT_EQ(one.index, 1);
  ASSERT_EQ(one.beams[0].intensity.size(), 500u);
  std::vector<int> lit;
  for (std::size_t j = 0; j < 500; ++j) {
    const std::uint8_t value = one.beams[0].intensity[j];
    if (value == 255) {
      lit.push_back(static_cast<int>(j));
    } else {
      EXPECT_EQ(value, 0) << j;
    }
  }
  EXPECT_EQ(lit, (std::vector<int>{19, 20}));  // bin j at (j + 1) x 0.1 m
  EXPECT_EQ(one.beams[1].intensity[29], 255);
  EXPECT_DOUBLE_EQ(one.beams[1].transducer_angle_rad, 198 * io::SonarSetup{}.step_rad);
  const SonarRevolution two = read_detected_revolution(tmp.path().string(), 2);
  ASSERT_EQ(two.beams.size(), 1u);
  EXPECT_EQ(two.beams[0].intensity[39], 255);
}

TEST(DetectedRevolution, AKeyframeBeyondTheFileNamesTheKeyframesItHolds) {
  const TempDir tmp;
  try {
    read_detected_revolution(detections_dataset(tmp), 3);
    ADD_FAILURE() << "no InputError";
  } catch (const io::InputError& e) {
    EXPECT_NE(std::string(e.what()).find("--keyframe 3: "), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("has keyframes 1..2"), std::string::npos) << e.what();
  }
  const TempDir empty;
  EXPECT_THROW(read_detected_revolution(empty.path().string(), 1), io::InputError);
}

}  // namespace
}  // namespace msislab::dataset
