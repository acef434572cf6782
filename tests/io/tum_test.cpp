// TUM trajectory files: round trips, the yaw extracted from the quaternion around 0, +-pi and the
// wrap-around, non-normalised quaternions, comments and the increasing-time rule.
#include "io/tum.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "geometry/angles.hpp"
#include "io/input_error.hpp"
#include "test_support.hpp"

namespace msislab::io {
namespace {

using testing::TempDir;
using testing::write_text;

constexpr double kYawTolerance_rad = 1e-15 * 8;

// The yaw read back from a file holding one pose with quaternion (qx, qy, qz, qw).
double yaw_of(double qx, double qy, double qz, double qw) {
  const TempDir dir;
  const std::string path = dir.file("q.tum");
  char buffer[256];
  std::snprintf(buffer, sizeof(buffer), "1 0 0 0 %.17g %.17g %.17g %.17g\n", qx, qy, qz, qw);
  write_text(path, buffer);
  return read_tum(path).front().yaw_rad;
}

// Wraps into (-pi, pi] so that yaw pi and -pi compare as the same angle.
double wrapped_difference(double a, double b) { return std::remainder(a - b, 2.0 * kPi); }

TEST(Tum, RoundTrip) {
  const TempDir dir;
  std::vector<TumPose> poses;
  for (int i = 0; i < 200; ++i) {
    const double yaw = -kPi + 2.0 * kPi * (i + 0.5) / 200.0;
    poses.push_back({1093455407.0 + 0.1 * i, 12.345678901234567 * i, -0.1 * i, -2.5, yaw});
  }
  write_tum(dir.file("a.tum"), poses);
  const std::vector<TumPose> back = read_tum(dir.file("a.tum"));
  ASSERT_EQ(back.size(), poses.size());
  for (std::size_t i = 0; i < poses.size(); ++i) {
    EXPECT_EQ(back[i].t_s, poses[i].t_s);
    EXPECT_EQ(back[i].x_m, poses[i].x_m);
    EXPECT_EQ(back[i].y_m, poses[i].y_m);
    EXPECT_EQ(back[i].z_m, poses[i].z_m);
    EXPECT_NEAR(back[i].yaw_rad, poses[i].yaw_rad, kYawTolerance_rad) << i;
  }
  EXPECT_EQ(testing::read_text(dir.file("a.tum")).rfind("# t x y z qx qy qz qw\n", 0), 0u);
  // A trajectory held in memory instead of the file carries yaw_as_stored: the file's bits.
  for (std::size_t i = 0; i < poses.size(); ++i) {
    EXPECT_EQ(back[i].yaw_rad, yaw_as_stored(poses[i].yaw_rad)) << i;
  }
}

TEST(Tum, YawAtZeroAndSmallAngles) {
  EXPECT_EQ(yaw_of(0, 0, 0, 1), 0.0);
  for (const double eps : {1e-12, -1e-12, 1e-300}) {
    const double yaw = yaw_of(0, 0, std::sin(eps / 2), std::cos(eps / 2));
    EXPECT_NEAR(yaw, eps, 1e-20) << eps;
    EXPECT_EQ(std::signbit(yaw), std::signbit(eps)) << eps;
  }
}

TEST(Tum, YawAtPlusMinusPiAndWrapAround) {
  EXPECT_NEAR(std::abs(yaw_of(0, 0, 1, 0)), kPi, kYawTolerance_rad);
  for (const double yaw : {kPi - 1e-9, -kPi + 1e-9, kPi + 0.25, -kPi - 0.25, 3 * kPi + 0.5}) {
    const double read = yaw_of(0, 0, std::sin(yaw / 2), std::cos(yaw / 2));
    EXPECT_LE(std::abs(read), kPi) << yaw;
    EXPECT_NEAR(wrapped_difference(read, yaw), 0.0, 1e-14) << yaw;
  }
  // q and -q are the same rotation.
  EXPECT_NEAR(yaw_of(0, 0, -std::sin(0.3), -std::cos(0.3)), 0.6, 1e-15);
}

TEST(Tum, NonNormalisedQuaternion) {
  EXPECT_NEAR(yaw_of(0, 0, 7 * std::sin(0.4), 7 * std::cos(0.4)), 0.8, 1e-15);
  EXPECT_NEAR(yaw_of(0, 0, 1e-200 * std::sin(0.4), 1e-200 * std::cos(0.4)), 0.8, 1e-15);
  EXPECT_NEAR(yaw_of(0, 0, 1e300 * std::sin(-1.2), 1e300 * std::cos(-1.2)), -2.4, 1e-15);
}

TEST(Tum, CommentsAndBlankLines) {
  const TempDir dir;
  const std::string path = write_text(dir.file("c.tum"),
                                      "# ground truth\r\n\r\n  # indented comment\n"
                                      "1.0 1 2 3 0 0 0 1\r\n"
                                      "\n2.0\t4  5 6 0 0 0.7071067811865476 0.7071067811865476\n");
  const auto poses = read_tum(path);
  ASSERT_EQ(poses.size(), 2u);
  EXPECT_EQ(poses[1].t_s, 2.0);
  EXPECT_EQ(poses[1].z_m, 6.0);
  EXPECT_NEAR(poses[1].yaw_rad, kPi / 2, 1e-15);
}

TEST(Tum, NonIncreasingTimesRejected) {
  const TempDir dir;
  const std::string equal = write_text(dir.file("e.tum"), "1 0 0 0 0 0 0 1\n1 0 0 0 0 0 0 1\n");
  EXPECT_THROW(read_tum(equal), InputError);
  const std::string backwards = write_text(dir.file("b.tum"), "2 0 0 0 0 0 0 1\n1 0 0 0 0 0 0 1\n");
  try {
    read_tum(backwards);
    FAIL() << "no InputError";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find(backwards + ":2: time does not increase (1 after 2)"),
              std::string::npos)
        << e.what();
  }
}

TEST(Tum, WriterRejectsNonFinite) {
  const TempDir dir;
  EXPECT_THROW(write_tum(dir.file("n.tum"), {{0.0, 0.0, 0.0, 0.0, std::nan("")}}), InputError);
}

}  // namespace
}  // namespace msislab::io
