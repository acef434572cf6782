// Column tables of the St. Pere navigation logs, private to stpere_logs.cpp: the names used in
// error messages, the separators of the original files and the header block written back. Each
// format's visit() walks a record's fields in file column order, so that reading, writing and
// comparing share one definition of the layout.
#pragma once

#include <array>
#include <cstddef>
#include <string_view>

#include "io/stpere_logs.hpp"

namespace msislab::io {

template <std::size_t N>
using ColumnText = std::array<std::string_view, N>;

struct DvlFormat {
  static constexpr bool kOptionalIdSensor = true;
  static constexpr ColumnText<32> kNames = {"logTime",
                                            "year",
                                            "month",
                                            "day",
                                            "hour",
                                            "minute",
                                            "second",
                                            "waterVelX",
                                            "waterVelY",
                                            "waterVelZ",
                                            "waterVelStatus",
                                            "bottomVelX",
                                            "bottomVelY",
                                            "bottomVelZ",
                                            "bottomVelStatus",
                                            "rangeBottom1",
                                            "rangeBottom2",
                                            "rangeBottom3",
                                            "amplitude1",
                                            "amplitude2",
                                            "amplitude3",
                                            "percentGoodPings",
                                            "heading",
                                            "pitch",
                                            "roll",
                                            "temperature",
                                            "pressure",
                                            "powerLevel",
                                            "slosv",
                                            "elosv",
                                            "distanceTravelX",
                                            "distanceTravelY"};
  // logTime, then the empty [idSensor] column (a double tab), then single spaces.
  static constexpr ColumnText<32> kSeparatorBefore = {
      "",  "\t\t", " ", " ", " ", " ", " ", " ", " ", " ", " ", " ", " ", " ", " ", " ",
      " ", " ",    " ", " ", " ", " ", " ", " ", " ", " ", " ", " ", " ", " ", " ", " "};
  static constexpr std::string_view kLineEnd = "";
  static constexpr std::string_view kHeader =
      "% ---------------------------------------\n"
      "% Data columns: \n"
      "% logTime (s), [idSensor], year, month, day, hour, minute, second, waterVelX (cm/s), "
      "waterVelY (cm/s), waterVelZ (cm/s), waterVelStatus, bottomVelX (cm/s), bottomVelY (cm/s), "
      "bottomVelZ (cm/s), bottomVelStatus, rangeBottom1, rangeBottom2, rangeBottom3, amplitude1, "
      "amplitude2, amplitude3, percentGoodPings, heading, pitch, roll, temperature, pressure, "
      "powerLevel, slosv, elosv, distanceTravelX, distanceTravelY\n"
      "% ---------------------------------------\n"
      "\n";

  template <typename Record, typename F>
  static void visit(Record& r, F&& f) {
    f(r.t_log_s);
    for (auto& v : r.dvl_clock) f(v);
    for (auto& v : r.water_vel_cm_s) f(v);
    f(r.water_vel_status);
    for (auto& v : r.bottom_vel_cm_s) f(v);
    f(r.bottom_vel_status);
    for (auto& v : r.range_bottom_m) f(v);
    for (auto& v : r.amplitude) f(v);
    f(r.percent_good_pings);
    f(r.heading_deg);
    f(r.pitch_deg);
    f(r.roll_deg);
    f(r.temperature_c);
    f(r.pressure);
    f(r.power_level);
    f(r.slosv);
    f(r.elosv);
    for (auto& v : r.distance_travel) f(v);
  }
};

struct MtiFormat {
  static constexpr bool kOptionalIdSensor = true;
  static constexpr ColumnText<10> kNames = {"logTime", "roll",  "pitch", "yaw",  "gyroX",
                                            "gyroY",   "gyroZ", "accX",  "accY", "accZ"};
  // Tab separated; the empty [idSensor] column and the empty group separators are double tabs.
  static constexpr ColumnText<10> kSeparatorBefore = {"",   "\t\t", "\t",   "\t", "\t\t",
                                                      "\t", "\t",   "\t\t", "\t", "\t"};
  static constexpr std::string_view kLineEnd = "\t\t";
  // The original header calls these position, velocity and acceleration; these are the real ones.
  static constexpr std::string_view kHeader =
      "% ---------------------------------------\n"
      "% Data columns: \n"
      "% logTime (s), [idSensor], roll (deg), pitch (deg), yaw (deg), gyroX (rad/s), "
      "gyroY (rad/s), gyroZ (rad/s), accelerationX (m/s^2), accelerationY (m/s^2), "
      "accelerationZ (m/s^2)\n"
      "% ---------------------------------------\n"
      "\n";

  template <typename Record, typename F>
  static void visit(Record& r, F&& f) {
    f(r.t_log_s);
    f(r.roll_deg);
    f(r.pitch_deg);
    f(r.yaw_deg);
    for (auto& v : r.gyro_rad_s) f(v);
    for (auto& v : r.accel_m_s2) f(v);
  }
};

struct GpsFormat {
  static constexpr bool kOptionalIdSensor = false;
  static constexpr ColumnText<10> kNames = {
      "logTime",        "latitude",   "longitude",      "status",  "altitude",
      "geoideAltitude", "trueCourse", "magneticCourse", "speedKn", "speedKmh"};
  static constexpr ColumnText<10> kSeparatorBefore = {"",   "\t", "\t", "\t", "\t",
                                                      "\t", "\t", "\t", "\t", "\t"};
  static constexpr std::string_view kLineEnd = "";
  static constexpr std::string_view kHeader =
      "% ---------------------------------------------------------------------------------------"
      "-------------\n"
      "% Data columns: \n"
      "% logTime (s), latitude (deg|min.fract_min), longitude (deg|min.fract_min), status (1=GPS "
      "2=DGPS), altitude (m), geoideAltitude (m), trueCourse(M-:), magneticCourse(M-:), "
      "speed(kts), speed(Km/h)\n"
      "% ---------------------------------------------------------------------------------------"
      "-------------\n"
      "\n";

  template <typename Record, typename F>
  static void visit(Record& r, F&& f) {
    f(r.t_log_s);
    f(r.latitude_nmea);
    f(r.longitude_nmea);
    f(r.status);
    f(r.altitude_m);
    f(r.geoid_altitude_m);
    f(r.true_course_deg);
    f(r.magnetic_course_deg);
    f(r.speed_kn);
    f(r.speed_kmh);
  }
};

// *_IS_timestamps.log has no header, like the original.
struct BeamTimeFormat {
  static constexpr bool kOptionalIdSensor = false;
  static constexpr ColumnText<2> kNames = {"logTime", "sensorTime"};
  static constexpr ColumnText<2> kSeparatorBefore = {"", " "};
  static constexpr std::string_view kLineEnd = "";
  static constexpr std::string_view kHeader = "";

  template <typename Record, typename F>
  static void visit(Record& r, F&& f) {
    f(r.t_log_s);
    f(r.sensor_time_ms);
  }
};

}  // namespace msislab::io
