// Readers and writers of the St. Pere log formats (../shared/datasets/stpere/README.md and
// docs/formats.md). Readers tolerate CRLF, tabs, runs of separators (empty columns), '%' header
// lines and blank lines, and reject anything else with InputError "file:line: what is wrong":
// wrong column count (truncated line), non-numeric, NaN or infinite fields, time going backwards.
// A missing or empty file (no data rows) is an error too. Writers produce files the readers read
// back exactly (shortest round-trip number formatting) and write atomically (temporary + rename).
#pragma once

#include <array>
#include <cstdint>
#include <string>
#include <vector>

namespace msislab::io {

/// One row of *_DVL.log (SonTek DVL), 32 columns (33 when the [idSensor] column is filled).
struct DvlRecord {
  double t_log_s = 0.0;
  std::array<double, 6> dvl_clock{};       ///< year, month, day, hour, minute, second
  std::array<double, 3> water_vel_cm_s{};  ///< DVL frame
  double water_vel_status = 0.0;
  std::array<double, 3> bottom_vel_cm_s{};  ///< DVL frame
  double bottom_vel_status = 0.0;           ///< 1 = valid bottom lock
  std::array<double, 3> range_bottom_m{};
  std::array<double, 3> amplitude{};
  double percent_good_pings = 0.0;
  double heading_deg = 0.0;  ///< the DVL's internal compass
  double pitch_deg = 0.0;
  double roll_deg = 0.0;
  double temperature_c = 0.0;
  double pressure = 0.0;
  double power_level = 0.0;
  double slosv = 0.0;
  double elosv = 0.0;
  std::array<double, 2> distance_travel{};
  bool operator==(const DvlRecord&) const;
};

/// One row of *_MTi.log (Xsens MTi), 10 columns (11 with a filled [idSensor] column).
struct MtiRecord {
  double t_log_s = 0.0;
  double roll_deg = 0.0;
  double pitch_deg = 0.0;
  double yaw_deg = 0.0;
  std::array<double, 3> gyro_rad_s{};
  std::array<double, 3> accel_m_s2{};
  bool operator==(const MtiRecord&) const;
};

/// One row of *_DGPS.log, 10 columns. Latitude and longitude stay in NMEA ddmm.mmmm form here;
/// nmea_to_degrees() converts.
struct GpsRecord {
  double t_log_s = 0.0;
  double latitude_nmea = 0.0;   ///< ddmm.mmmm, negative = south
  double longitude_nmea = 0.0;  ///< dddmm.mmmm, negative = west
  double status = 0.0;          ///< 1 = GPS, 2 = DGPS
  double altitude_m = 0.0;
  double geoid_altitude_m = 0.0;
  double true_course_deg = 0.0;
  double magnetic_course_deg = 0.0;
  double speed_kn = 0.0;
  double speed_kmh = 0.0;
  bool operator==(const GpsRecord&) const;
};

/// *_SETUP.log: one row "range_m bin_m step_rad".
struct SonarSetup {
  double range_m = 50.0;
  double bin_m = 0.1;
  double step_rad = 0.031415926535897934;
  bool operator==(const SonarSetup&) const;
};

/// Transducer steps in 360 deg: 2 pi / step_rad, rounded (200 at St. Pere).
int steps_per_revolution(const SonarSetup& setup);

/// One row of a raw *_IS.log: a sonar beam with its echo intensity profile (bin i at i x bin_m).
struct SonarBeamRecord {
  double t_log_s = 0.0;
  double sensor_time_ms = 0.0;
  double transducer_angle_rad = 0.0;
  std::vector<std::uint8_t> intensity;  ///< 0..255 per bin; every row has the same count
  bool operator==(const SonarBeamRecord&) const;
};

/// One row of *_IS_timestamps.log: "logTime_s sensorTime_ms".
struct BeamTimeRecord {
  double t_log_s = 0.0;
  double sensor_time_ms = 0.0;
  bool operator==(const BeamTimeRecord&) const;
};

/// Converts NMEA ddmm.mmmm (or dddmm.mmmm) to decimal degrees, keeping the sign.
double nmea_to_degrees(double ddmm);
/// Decimal degrees to NMEA ddmm.mmmm, keeping the sign.
double degrees_to_nmea(double degrees);

std::vector<DvlRecord> read_dvl_log(const std::string& path);
void write_dvl_log(const std::string& path, const std::vector<DvlRecord>& rows);

std::vector<MtiRecord> read_mti_log(const std::string& path);
void write_mti_log(const std::string& path, const std::vector<MtiRecord>& rows);

std::vector<GpsRecord> read_gps_log(const std::string& path);
void write_gps_log(const std::string& path, const std::vector<GpsRecord>& rows);

SonarSetup read_setup_log(const std::string& path);
void write_setup_log(const std::string& path, const SonarSetup& setup);

/// Raw sonar beams. Header lines ('%') are skipped; every row must have the same bin count
/// (at least 1) and integer intensities 0..255.
std::vector<SonarBeamRecord> read_is_log(const std::string& path);
void write_is_log(const std::string& path, const std::vector<SonarBeamRecord>& rows);

std::vector<BeamTimeRecord> read_beam_times_log(const std::string& path);
void write_beam_times_log(const std::string& path, const std::vector<BeamTimeRecord>& rows);

}  // namespace msislab::io
