// The St. Pere log readers on the real files (row counts and first rows from the dataset README),
// write -> read round trips that must be exact, and the layouts the originals use (CRLF, tabs,
// empty columns, '%' headers).
#include "io/stpere_logs.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <random>

#include "io/input_error.hpp"
#include "test_support.hpp"

namespace msislab::io {
namespace {

using testing::read_text;
using testing::TempDir;
using testing::write_text;

std::string stpere_file(const std::string& suffix) {
  return testing::stpere_dir() + "/_040825_1735_" + suffix;
}

// Doubles over many magnitudes and signs, with full 17-digit mantissas, to stress the formatting.
class RandomValues {
 public:
  explicit RandomValues(unsigned seed) : rng_(seed) {}
  double any() {
    const double mantissa = std::uniform_real_distribution<double>(-1.0, 1.0)(rng_);
    const int exponent = std::uniform_int_distribution<int>(-30, 30)(rng_);
    return std::ldexp(mantissa, exponent);
  }
  std::vector<double> increasing_times(std::size_t n) {
    std::vector<double> t(n);
    for (double& v : t) v = 1.09e9 + std::uniform_real_distribution<double>(0.0, 4000.0)(rng_);
    std::sort(t.begin(), t.end());
    return t;
  }
  std::uint8_t bin() {
    return static_cast<std::uint8_t>(std::uniform_int_distribution<int>(0, 255)(rng_));
  }

 private:
  std::mt19937_64 rng_;
};

template <typename Record, typename Visit>
std::vector<Record> random_rows(std::size_t n, unsigned seed, Visit fill) {
  RandomValues random(seed);
  const std::vector<double> times = random.increasing_times(n);
  std::vector<Record> rows(n);
  for (std::size_t i = 0; i < n; ++i) {
    fill(rows[i], random);
    rows[i].t_log_s = times[i];
  }
  return rows;
}

TEST(StPereLogs, RealDvlLog) {
  MSISLAB_REQUIRE_STPERE();
  const std::vector<DvlRecord> rows = read_dvl_log(stpere_file("DVL.log"));
  ASSERT_EQ(rows.size(), 5045u);
  const auto valid = std::count_if(rows.begin(), rows.end(),
                                   [](const DvlRecord& r) { return r.bottom_vel_status == 1.0; });
  EXPECT_EQ(valid, 4961);
  const DvlRecord& first = rows.front();
  EXPECT_EQ(first.t_log_s, 1093455407.147);
  EXPECT_EQ(first.dvl_clock, (std::array<double, 6>{2007, 3, 16, 13, 0, 56}));
  EXPECT_EQ(first.water_vel_cm_s, (std::array<double, 3>{38.2, -47.0, 1.8}));
  EXPECT_EQ(first.bottom_vel_cm_s, (std::array<double, 3>{6.1, -4.9, 2.8}));
  EXPECT_EQ(first.bottom_vel_status, 1.0);
  EXPECT_EQ(first.range_bottom_m, (std::array<double, 3>{1.84, 1.88, 1.86}));
  EXPECT_EQ(first.heading_deg, 207.7);
  EXPECT_EQ(first.temperature_c, 14.27);
  EXPECT_EQ(first.distance_travel, (std::array<double, 2>{0.08, -0.25}));
  EXPECT_EQ(rows.back().t_log_s, 1093458750.569);
  EXPECT_EQ(rows.back().distance_travel, (std::array<double, 2>{268.71, 557.14}));
}

TEST(StPereLogs, RealMtiLog) {
  MSISLAB_REQUIRE_STPERE();
  const std::vector<MtiRecord> rows = read_mti_log(stpere_file("MTi.log"));
  ASSERT_EQ(rows.size(), 33457u);
  const MtiRecord& first = rows.front();
  EXPECT_EQ(first.t_log_s, 1093455407.042);
  EXPECT_EQ(first.roll_deg, 0.506328);
  EXPECT_EQ(first.pitch_deg, -2.5422);
  EXPECT_EQ(first.yaw_deg, -126.276);
  EXPECT_EQ(first.gyro_rad_s, (std::array<double, 3>{0.0115654, -0.00641596, 0.00508943}));
  EXPECT_EQ(first.accel_m_s2, (std::array<double, 3>{-0.427074, -0.0795686, -9.77331}));
  EXPECT_EQ(rows.back().t_log_s, 1093458752.987);
}

TEST(StPereLogs, RealGpsLog) {
  MSISLAB_REQUIRE_STPERE();
  const std::vector<GpsRecord> rows = read_gps_log(stpere_file("DGPS.log"));
  ASSERT_EQ(rows.size(), 3342u);
  const GpsRecord& first = rows.front();
  EXPECT_EQ(first.t_log_s, 1093455407.9);
  EXPECT_EQ(first.latitude_nmea, 4212.225);
  EXPECT_EQ(first.longitude_nmea, 306.2832);
  EXPECT_EQ(first.status, 1.0);
  EXPECT_EQ(first.altitude_m, -2.1);
  EXPECT_EQ(first.geoid_altitude_m, 51.8);
  EXPECT_EQ(first.true_course_deg, 23.6);
  EXPECT_EQ(first.magnetic_course_deg, 24.0);
  EXPECT_EQ(first.speed_kn, 0.1);
  EXPECT_EQ(first.speed_kmh, 0.1);
  EXPECT_TRUE(
      std::all_of(rows.begin(), rows.end(), [](const GpsRecord& r) { return r.status == 1.0; }));
}

TEST(StPereLogs, RealBeamTimesAndSetup) {
  MSISLAB_REQUIRE_STPERE();
  const std::vector<BeamTimeRecord> times = read_beam_times_log(stpere_file("IS_timestamps.log"));
  ASSERT_EQ(times.size(), 46259u);
  EXPECT_EQ(times.front(), (BeamTimeRecord{1093455224.578, 63224578}));
  EXPECT_EQ(times.back(), (BeamTimeRecord{1093458427.111, 66427110}));

  const SonarSetup setup = read_setup_log(stpere_file("SETUP.log"));
  EXPECT_EQ(setup.range_m, 50.0);
  EXPECT_EQ(setup.bin_m, 0.1);
  EXPECT_EQ(setup.step_rad, 0.03141592653590);
  constexpr double kPi = 3.14159265358979323846;
  EXPECT_NEAR(setup.step_rad, 2.0 * kPi / 200.0, 1e-13);
}

// Real file -> write -> read gives the same records, bit for bit.
template <typename Read, typename Write>
void expect_real_round_trip(const std::string& suffix, Read read, Write write) {
  const TempDir dir;
  const auto original = read(stpere_file(suffix));
  const std::string copy = dir.file("copy_" + suffix);
  write(copy, original);
  EXPECT_TRUE(read(copy) == original) << suffix;
}

TEST(StPereLogs, RealFilesRoundTrip) {
  MSISLAB_REQUIRE_STPERE();
  expect_real_round_trip("DVL.log", read_dvl_log, write_dvl_log);
  expect_real_round_trip("MTi.log", read_mti_log, write_mti_log);
  expect_real_round_trip("DGPS.log", read_gps_log, write_gps_log);
  expect_real_round_trip("IS_timestamps.log", read_beam_times_log, write_beam_times_log);
  expect_real_round_trip("SETUP.log", read_setup_log, write_setup_log);
}

TEST(StPereLogs, DvlRoundTripAndLayout) {
  const TempDir dir;
  const auto rows = random_rows<DvlRecord>(50, 1, [](DvlRecord& r, RandomValues& random) {
    for (double& v : r.dvl_clock) v = random.any();
    for (double& v : r.water_vel_cm_s) v = random.any();
    for (double& v : r.bottom_vel_cm_s) v = random.any();
    for (double& v : r.range_bottom_m) v = random.any();
    for (double& v : r.amplitude) v = random.any();
    for (double& v : r.distance_travel) v = random.any();
    r.bottom_vel_status = 1.0;
    r.heading_deg = random.any();
    r.elosv = 1e-300;
    r.pressure = -1e300;
  });
  const std::string path = dir.file("x_DVL.log");
  write_dvl_log(path, rows);
  EXPECT_EQ(read_dvl_log(path), rows);
  const std::string text = read_text(path);
  EXPECT_EQ(text.front(), '%');
  EXPECT_NE(text.find("\n\n"), std::string::npos) << "blank line after the header";
  EXPECT_NE(text.find("\t\t"), std::string::npos) << "empty [idSensor] column";
}

TEST(StPereLogs, MtiRoundTrip) {
  const TempDir dir;
  const auto rows = random_rows<MtiRecord>(50, 2, [](MtiRecord& r, RandomValues& random) {
    r.roll_deg = random.any();
    r.pitch_deg = random.any();
    r.yaw_deg = random.any();
    for (double& v : r.gyro_rad_s) v = random.any();
    for (double& v : r.accel_m_s2) v = random.any();
  });
  const std::string path = dir.file("x_MTi.log");
  write_mti_log(path, rows);
  EXPECT_EQ(read_mti_log(path), rows);
  EXPECT_NE(read_text(path).find("\t\t"), std::string::npos);
}

TEST(StPereLogs, GpsRoundTrip) {
  const TempDir dir;
  const auto rows = random_rows<GpsRecord>(50, 3, [](GpsRecord& r, RandomValues& random) {
    r.latitude_nmea = 4212.0 + random.any();
    r.longitude_nmea = -306.0 + random.any();
    r.status = 2.0;
    r.altitude_m = random.any();
    r.geoid_altitude_m = random.any();
    r.true_course_deg = random.any();
    r.magnetic_course_deg = random.any();
    r.speed_kn = random.any();
    r.speed_kmh = random.any();
  });
  const std::string path = dir.file("x_DGPS.log");
  write_gps_log(path, rows);
  EXPECT_EQ(read_gps_log(path), rows);
}

TEST(StPereLogs, BeamTimesAndSetupRoundTrip) {
  const TempDir dir;
  const auto rows = random_rows<BeamTimeRecord>(
      100, 4, [](BeamTimeRecord& r, RandomValues& random) { r.sensor_time_ms = random.any(); });
  write_beam_times_log(dir.file("t.log"), rows);
  EXPECT_EQ(read_beam_times_log(dir.file("t.log")), rows);

  const SonarSetup setup{75.5, 0.0123456789012345, 0.031415926535897934};
  write_setup_log(dir.file("setup.log"), setup);
  EXPECT_EQ(read_setup_log(dir.file("setup.log")), setup);
}

TEST(StPereLogs, IsLogRoundTripWithRandomBins) {
  const TempDir dir;
  auto rows = random_rows<SonarBeamRecord>(40, 5, [](SonarBeamRecord& r, RandomValues& random) {
    r.sensor_time_ms = std::round(std::abs(random.any()) * 1e6);
    r.transducer_angle_rad = random.any();
    r.intensity.resize(37);
    for (std::uint8_t& bin : r.intensity) bin = random.bin();
  });
  rows[0].intensity.front() = 0;
  rows[0].intensity.back() = 255;
  const std::string path = dir.file("x_IS.log");
  write_is_log(path, rows);
  EXPECT_EQ(read_is_log(path), rows);

  const std::string text = read_text(path);
  std::size_t header_lines = 0;
  for (std::size_t at = 0; at < text.size() && text[at] == '%'; at = text.find('\n', at) + 1)
    ++header_lines;
  EXPECT_EQ(header_lines, 8u);
}

TEST(StPereLogs, NmeaConversionBothWays) {
  EXPECT_NEAR(nmea_to_degrees(4212.225), 42.0 + 12.225 / 60.0, 1e-12);
  EXPECT_NEAR(nmea_to_degrees(306.2832), 3.0 + 6.2832 / 60.0, 1e-12);
  EXPECT_NEAR(nmea_to_degrees(-4212.225), -(42.0 + 12.225 / 60.0), 1e-12);
  EXPECT_NEAR(nmea_to_degrees(-306.2832), -(3.0 + 6.2832 / 60.0), 1e-12);
  EXPECT_EQ(nmea_to_degrees(0.0), 0.0);
  EXPECT_NEAR(nmea_to_degrees(59.9999), 59.9999 / 60.0, 1e-12);
  EXPECT_NEAR(degrees_to_nmea(42.0 + 12.225 / 60.0), 4212.225, 1e-9);
  EXPECT_NEAR(degrees_to_nmea(-(3.0 + 6.2832 / 60.0)), -306.2832, 1e-9);
  for (const double nmea : {4212.225, -4212.225, 306.2832, -306.2832, 0.5, -17959.99, 9000.0})
    EXPECT_NEAR(degrees_to_nmea(nmea_to_degrees(nmea)), nmea, 1e-9) << nmea;
}

TEST(StPereLogs, ToleratesCrlfTabsMixedSeparatorsAndHeaders) {
  const TempDir dir;
  const std::string gps =
      write_text(dir.file("gps.log"),
                 "% header\r\n%\tmore\r\n\r\n   \t\r\n"
                 "  1.5\t4212.225 \t 306.2832\t1 -2.1  51.8\t\t23.6 24 0.1 0.1\r\n"
                 "\t% an indented comment\r\n"
                 "2.5 4212.2 306.3 1 -2.1 51.8 23.6 24 0.1 0.2");
  const std::vector<GpsRecord> rows = read_gps_log(gps);
  ASSERT_EQ(rows.size(), 2u);
  EXPECT_EQ(rows[0], (GpsRecord{1.5, 4212.225, 306.2832, 1, -2.1, 51.8, 23.6, 24, 0.1, 0.1}));
  EXPECT_EQ(rows[1].speed_kmh, 0.2);

  const std::string setup = write_text(dir.file("setup.log"), "50 0.1 0.03141592653590");
  EXPECT_EQ(read_setup_log(setup), (SonarSetup{50, 0.1, 0.03141592653590}));
}

TEST(StPereLogs, AcceptsAFilledIdSensorColumn) {
  const TempDir dir;
  const std::string empty_id =
      write_text(dir.file("a.log"), "1.5\t\t0.5\t-2.5\t-126\t\t1\t2\t3\t\t4\t5\t6\t\t\r\n");
  const std::string filled_id =
      write_text(dir.file("b.log"), "1.5\t7\t0.5\t-2.5\t-126\t\t1\t2\t3\t\t4\t5\t6\t\t\r\n");
  EXPECT_EQ(read_mti_log(empty_id), read_mti_log(filled_id));
  EXPECT_EQ(read_mti_log(filled_id).front().yaw_deg, -126.0);

  std::string dvl;
  for (int i = 0; i < 31; ++i) dvl += " " + std::to_string(i + 2);
  write_text(dir.file("c.log"), "1" + dvl + "\n");
  write_text(dir.file("d.log"), "1 99" + dvl + "\n");
  EXPECT_EQ(read_dvl_log(dir.file("c.log")), read_dvl_log(dir.file("d.log")));
  EXPECT_EQ(read_dvl_log(dir.file("d.log")).front().distance_travel[1], 32.0);
}

TEST(StPereLogs, EqualTimesAreAllowed) {
  const TempDir dir;
  const std::string path = write_text(dir.file("t.log"), "5 1\n5 2\n6 3\n");
  EXPECT_EQ(read_beam_times_log(path).size(), 3u);
}

TEST(StPereLogs, WritersRejectNonFiniteValues) {
  const TempDir dir;
  std::vector<MtiRecord> rows(3);
  rows[1].yaw_deg = std::nan("");
  const std::string path = dir.file("bad_MTi.log");
  try {
    write_mti_log(path, rows);
    FAIL() << "no InputError";
  } catch (const InputError& e) {
    const std::string message = e.what();
    EXPECT_NE(message.find(path), std::string::npos) << message;
    EXPECT_NE(message.find("row 2"), std::string::npos) << message;
    EXPECT_NE(message.find("yaw"), std::string::npos) << message;
  }
  EXPECT_FALSE(std::filesystem::exists(path));

  std::vector<SonarBeamRecord> beams(1);
  beams[0].intensity = {1, 2};
  beams[0].transducer_angle_rad = INFINITY;
  EXPECT_THROW(write_is_log(dir.file("bad_IS.log"), beams), InputError);
  EXPECT_THROW(write_setup_log(dir.file("s.log"), SonarSetup{50, -INFINITY, 0.1}), InputError);
}

TEST(StPereLogs, IsLogWriterRejectsDifferingBinCounts) {
  const TempDir dir;
  std::vector<SonarBeamRecord> beams(2);
  beams[0].intensity = {1, 2, 3};
  beams[1].intensity = {1, 2};
  EXPECT_THROW(write_is_log(dir.file("x_IS.log"), beams), InputError);
}

}  // namespace
}  // namespace msislab::io
