// LocalProjection: WGS84 latitude/longitude <-> local UTM metres relative to the frame origin,
// checked against reference coordinates computed independently with PROJ's cs2cs.
#include "io/geodesy.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "io/input_error.hpp"

namespace msislab::io {
namespace {

constexpr double kMillimetre = 1e-3;
constexpr double kRoundTripTolerance_deg = 1e-9;

// The St. Pere origin: the first GPS fix, 42 deg 12.225 min N, 3 deg 6.2832 min E.
constexpr double kOriginLat_deg = 42.0 + 12.225 / 60.0;
constexpr double kOriginLon_deg = 3.0 + 6.2832 / 60.0;

// Reference UTM 31N (EPSG:32631) easting/northing in metres, computed with PROJ 9.1.1:
//   printf "LAT LON\n" | cs2cs -f "%.9f" EPSG:4326 EPSG:32631
// (EPSG:4326 input in its authority axis order: latitude first; output easting, northing).
struct UtmReference {
  double lat_deg;
  double lon_deg;
  double easting_m;
  double northing_m;
};
constexpr UtmReference kOriginUtm = {42.20375, 3.10472, 508644.940391571, 4672404.064009894};
constexpr UtmReference kStPerePoints[] = {
    {42.20475, 3.10472, 508644.804064182, 4672515.096848746},  // 0.001 deg north
    {42.20375, 3.10572, 508727.493307565, 4672404.165852283},  // 0.001 deg east
    {42.20200, 3.10750, 508874.682398491, 4672210.042103519},  // ~300 m south-east
};

LocalFrame frame_at(double lat_deg, double lon_deg) {
  LocalFrame frame;
  frame.origin_latitude_deg = lat_deg;
  frame.origin_longitude_deg = lon_deg;
  return frame;
}

TEST(Geodesy, StPereOriginIsTheLocalOrigin) {
  // The reference table's origin is the St. Pere origin.
  ASSERT_NEAR(kOriginUtm.lat_deg, kOriginLat_deg, 1e-12);
  ASSERT_NEAR(kOriginUtm.lon_deg, kOriginLon_deg, 1e-12);
  const LocalProjection projection(LocalFrame{});
  EXPECT_EQ(projection.utm_epsg(), 32631);
  const Eigen::Vector2d p = projection.to_local(kOriginLat_deg, kOriginLon_deg);
  EXPECT_NEAR(p.x(), 0.0, 1e-9);
  EXPECT_NEAR(p.y(), 0.0, 1e-9);
}

TEST(Geodesy, LocalOffsetsMatchCs2cs) {
  const LocalProjection projection(frame_at(kOriginLat_deg, kOriginLon_deg));
  for (const UtmReference& ref : kStPerePoints) {
    SCOPED_TRACE(::testing::Message() << ref.lat_deg << ", " << ref.lon_deg);
    const Eigen::Vector2d p = projection.to_local(ref.lat_deg, ref.lon_deg);
    EXPECT_NEAR(p.x(), ref.easting_m - kOriginUtm.easting_m, kMillimetre);
    EXPECT_NEAR(p.y(), ref.northing_m - kOriginUtm.northing_m, kMillimetre);
  }
}

TEST(Geodesy, ThousandthOfADegreeNorthIsAbout111MetresNorth) {
  const LocalProjection projection(LocalFrame{});
  const Eigen::Vector2d p = projection.to_local(kOriginLat_deg + 0.001, kOriginLon_deg);
  // Grid north differs from true north by the meridian convergence (~0.07 deg here).
  EXPECT_NEAR(p.x(), 0.0, 0.5);
  EXPECT_NEAR(p.y(), 111.03, 0.05);
}

TEST(Geodesy, RoundTripToGeodetic) {
  const LocalProjection projection(LocalFrame{});
  const double points[][2] = {{kOriginLat_deg, kOriginLon_deg},
                              {42.20475, 3.10472},
                              {42.19, 3.09},
                              {42.25, 3.2},
                              {41.9, 2.8},
                              {42.5, 3.5}};
  for (const auto& point : points) {
    SCOPED_TRACE(::testing::Message() << point[0] << ", " << point[1]);
    const auto [lat_deg, lon_deg] = projection.to_geodetic(projection.to_local(point[0], point[1]));
    EXPECT_NEAR(lat_deg, point[0], kRoundTripTolerance_deg);
    EXPECT_NEAR(lon_deg, point[1], kRoundTripTolerance_deg);
  }
  // And from local metres: geodetic and back.
  for (const Eigen::Vector2d& p_m :
       {Eigen::Vector2d(0, 0), Eigen::Vector2d(250.5, -120.25), Eigen::Vector2d(-3000, 5000)}) {
    const auto [lat_deg, lon_deg] = projection.to_geodetic(p_m);
    const Eigen::Vector2d back = projection.to_local(lat_deg, lon_deg);
    EXPECT_NEAR((back - p_m).norm(), 0.0, 1e-6) << p_m.transpose();
  }
}

TEST(Geodesy, SouthernHemisphereOriginPicksUtmSouth) {
  // Sydney, zone 56 south. Reference: printf -- "LAT LON\n" | cs2cs -f "%.9f" EPSG:4326 EPSG:32756
  const LocalProjection projection(frame_at(-33.86, 151.21));
  EXPECT_EQ(projection.utm_epsg(), 32756);
  const Eigen::Vector2d p = projection.to_local(-33.85, 151.22);
  EXPECT_NEAR(p.x(), 335322.356994809 - 334416.393989653, kMillimetre);
  EXPECT_NEAR(p.y(), 6253050.383185945 - 6251925.360352391, kMillimetre);
  const auto [lat_deg, lon_deg] = projection.to_geodetic(p);
  EXPECT_NEAR(lat_deg, -33.85, kRoundTripTolerance_deg);
  EXPECT_NEAR(lon_deg, 151.22, kRoundTripTolerance_deg);
}

TEST(Geodesy, ZoneFromLongitude) {
  EXPECT_EQ(LocalProjection(frame_at(40.4, -3.7)).utm_epsg(), 32630);    // Madrid
  EXPECT_EQ(LocalProjection(frame_at(-12.0, -77.0)).utm_epsg(), 32718);  // Lima
  EXPECT_EQ(LocalProjection(frame_at(10.0, -179.5)).utm_epsg(), 32601);
  EXPECT_EQ(LocalProjection(frame_at(10.0, 179.5)).utm_epsg(), 32660);
}

TEST(Geodesy, OriginOutsideUtmThrows) {
  EXPECT_THROW(LocalProjection(frame_at(89.0, 3.0)), InputError);
  EXPECT_THROW(LocalProjection(frame_at(-89.0, 3.0)), InputError);
  EXPECT_THROW(LocalProjection(frame_at(42.0, 181.0)), InputError);
  const double nan = std::numeric_limits<double>::quiet_NaN();
  EXPECT_THROW(LocalProjection(frame_at(nan, 3.0)), InputError);
  try {
    const LocalProjection projection(frame_at(89.0, 3.0));
    ADD_FAILURE() << "no InputError at latitude 89";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("89"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace msislab::io
