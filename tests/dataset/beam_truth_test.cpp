// truth/beams.csv: a simulation's beams (dataset::beam_truth_rows) round trip exactly through
// io::write_beam_truth and io::read_beam_truth, and malformed files are rejected
// with file:line messages.
#include "io/beam_truth.hpp"

#include <gtest/gtest.h>

#include "dataset/sim_dataset.hpp"
#include "io/input_error.hpp"
#include "test_support.hpp"

namespace msislab::dataset {
namespace {

using testing::TempDir;

constexpr const char* kHeader =
    "t_s,x_m,y_m,yaw_rad,bearing_rad,first_hit_range_m,strongest_range_m,strongest_multipath,"
    "strongest_surface,strongest_bearing_offset_rad\n";

std::vector<sim::RenderedBeam> sample_beams() {
  std::vector<sim::RenderedBeam> beams(3);
  beams[0].slot.t_s = 1093455407.0;
  beams[0].truth.vehicle = Pose2(1.25, -3.5, 0.1);
  beams[0].truth.bearing_vehicle_rad = 3.141592653589793;
  beams[0].truth.first_hit_range_m = 12.345678901234567;
  beams[0].truth.strongest_range_m = 12.4;
  beams[0].truth.strongest_surface = "walls";
  beams[0].truth.strongest_bearing_offset_rad = -0.0123456789012345;
  beams[1].slot.t_s = 1093455407.069;
  beams[1].truth.vehicle = Pose2(1.26, -3.5, -3.0);
  beams[1].truth.strongest_range_m = 8.1;  // no first hit: the bottom band only
  beams[1].truth.strongest_surface = "bottom";
  beams[2].slot.t_s = 1093455407.138;
  beams[2].truth.first_hit_range_m = 40.0;
  beams[2].truth.strongest_range_m = 44.5;
  beams[2].truth.strongest_is_multipath = true;
  beams[2].truth.strongest_surface = "water_surface";
  beams[2].truth.strongest_bearing_offset_rad = 0.07;
  return beams;
}

TEST(BeamTruth, RoundTripIsExact) {
  const TempDir dir;
  const std::vector<sim::RenderedBeam> beams = sample_beams();
  io::write_beam_truth(dir.file("beams.csv"), beam_truth_rows(beams));
  const std::vector<io::BeamTruthRow> rows = io::read_beam_truth(dir.file("beams.csv"));
  ASSERT_EQ(rows.size(), beams.size());
  for (std::size_t i = 0; i < rows.size(); ++i) {
    const sim::BeamTruth& t = beams[i].truth;
    EXPECT_EQ(rows[i].t_s, beams[i].slot.t_s);
    EXPECT_EQ(rows[i].x_m, t.vehicle.x());
    EXPECT_EQ(rows[i].y_m, t.vehicle.y());
    EXPECT_EQ(rows[i].yaw_rad, t.vehicle.yaw());
    EXPECT_EQ(rows[i].bearing_rad, t.bearing_vehicle_rad);
    EXPECT_EQ(rows[i].first_hit_range_m, t.first_hit_range_m);
    EXPECT_EQ(rows[i].strongest_range_m, t.strongest_range_m);
    EXPECT_EQ(rows[i].strongest_multipath, t.strongest_is_multipath);
    EXPECT_EQ(rows[i].strongest_surface, t.strongest_surface);
    EXPECT_EQ(rows[i].strongest_bearing_offset_rad, t.strongest_bearing_offset_rad);
  }
  EXPECT_FALSE(rows[1].first_hit_range_m.has_value());
  EXPECT_FALSE(rows[1].strongest_bearing_offset_rad.has_value());
}

TEST(BeamTruth, AcceptsCrlfAndBlankLines) {
  const TempDir dir;
  const std::string path = testing::write_text(
      dir.file("beams.csv"),
      "t_s,x_m,y_m,yaw_rad,bearing_rad,first_hit_range_m,strongest_range_m,strongest_multipath,"
      "strongest_surface,strongest_bearing_offset_rad\r\n1,2,3,0.5,1.5,,7.5,0,bottom,"
      "\r\n\r\n2,2,3,0.5,1.5,9,9.1,1,walls,0.01\r\n");
  const std::vector<io::BeamTruthRow> rows = io::read_beam_truth(path);
  ASSERT_EQ(rows.size(), 2u);
  EXPECT_FALSE(rows[0].first_hit_range_m);
  EXPECT_EQ(rows[1].first_hit_range_m, 9.0);
  EXPECT_TRUE(rows[1].strongest_multipath);
  EXPECT_EQ(rows[1].strongest_surface, "walls");
  EXPECT_EQ(rows[1].strongest_bearing_offset_rad, 0.01);
}

// Reading `body` after the header must fail with a message containing `expected`.
void expect_rejected(const std::string& body, const std::string& expected,
                     const std::string& header = kHeader) {
  const TempDir dir;
  const std::string path = testing::write_text(dir.file("beams.csv"), header + body);
  try {
    io::read_beam_truth(path);
    ADD_FAILURE() << "accepted: " << body;
  } catch (const io::InputError& e) {
    EXPECT_NE(std::string(e.what()).find(expected), std::string::npos)
        << "message: " << e.what() << "\nexpected to contain: " << expected;
  }
}

TEST(BeamTruth, RejectsMalformedFiles) {
  const std::string good = "1,2,3,0.5,1.5,9,9.1,0,walls,0.01\n";
  expect_rejected(good, "beams.csv:1: wrong header", "t_s,x_m,y_m\n");
  expect_rejected("", "beams.csv: no data rows");
  expect_rejected(good + "2,2,3,0.5,1.5,9\n", "beams.csv:3: truncated line: expected 10");
  expect_rejected(good + "2,2,3,0.5,1.5,9,9.1,0,walls,0,x\n", "beams.csv:3: too many fields");
  expect_rejected(good + "2,2,abc,0.5,1.5,9,9.1,0,walls,0\n", "beams.csv:3: field 3 (y_m) 'abc'");
  expect_rejected(good + "2,2,3,0.5,,9,9.1,0,walls,0\n", "beams.csv:3: field 5 (bearing_rad)");
  expect_rejected(good + "2,2,3,0.5,1.5,nan,9.1,0,walls,0\n", "field 6 (first_hit_range_m)");
  expect_rejected(good + "2,2,3,0.5,1.5,9,9.1,2,walls,0\n", "field 8 (strongest_multipath) '2'");
  expect_rejected(good + "2,2,3,0.5,1.5,9,9.1,0,walls,inf\n",
                  "field 10 (strongest_bearing_offset_rad)");
  expect_rejected(good + "0.5,2,3,0.5,1.5,9,9.1,0,walls,0\n", "beams.csv:3: t_s goes backwards");
}

// A dataset simulated before the strongest echo's bearing was written has 9 columns: it is read,
// with no bearing; a 10th field under that header is too many.
TEST(BeamTruth, ReadsDatasetsWithoutTheBearingColumn) {
  const TempDir dir;
  const std::string old_header =
      "t_s,x_m,y_m,yaw_rad,bearing_rad,first_hit_range_m,strongest_range_m,strongest_multipath,"
      "strongest_surface\n";
  const std::string path =
      testing::write_text(dir.file("beams.csv"), old_header + "1,2,3,0.5,1.5,9,9.1,0,walls\n");
  const std::vector<io::BeamTruthRow> rows = io::read_beam_truth(path);
  ASSERT_EQ(rows.size(), 1u);
  EXPECT_EQ(rows[0].strongest_range_m, 9.1);
  EXPECT_FALSE(rows[0].strongest_bearing_offset_rad);
  expect_rejected("1,2,3,0.5,1.5,9,9.1,0,walls,0.01\n", "beams.csv:2: too many fields", old_header);
  // With Windows line ends too.
  const std::string crlf =
      testing::write_text(dir.file("crlf.csv"), old_header.substr(0, old_header.size() - 1) +
                                                    "\r\n1,2,3,0.5,1.5,9,9.1,0,walls\r\n");
  EXPECT_FALSE(io::read_beam_truth(crlf).at(0).strongest_bearing_offset_rad);
}

TEST(BeamTruth, RejectsMissingAndEmptyFiles) {
  const TempDir dir;
  EXPECT_THROW(io::read_beam_truth(dir.file("absent.csv")), io::InputError);
  const std::string empty = testing::write_text(dir.file("empty.csv"), "");
  EXPECT_THROW(io::read_beam_truth(empty), io::InputError);
}

}  // namespace
}  // namespace msislab::dataset
