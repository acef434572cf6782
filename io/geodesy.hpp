// Geodetic latitude/longitude (WGS84) <-> the local world frame: UTM metres (zone and hemisphere of
// the frame's origin) relative to the origin. The projection is PROJ's, not hand-written.
#pragma once

#include <Eigen/Core>
#include <memory>
#include <utility>

#include "geometry/calibration.hpp"

namespace msislab::io {

class LocalProjection {
 public:
  /// Throws InputError when PROJ cannot build the transformation.
  explicit LocalProjection(const LocalFrame& frame);
  ~LocalProjection();
  LocalProjection(const LocalProjection&) = delete;
  LocalProjection& operator=(const LocalProjection&) = delete;

  /// Local x East, y North (m) of a WGS84 latitude/longitude in degrees.
  Eigen::Vector2d to_local(double latitude_deg, double longitude_deg) const;
  /// WGS84 (latitude_deg, longitude_deg) of a local position.
  std::pair<double, double> to_geodetic(const Eigen::Vector2d& p_local_m) const;
  /// EPSG code of the UTM zone in use (326zz north, 327zz south).
  int utm_epsg() const { return utm_epsg_; }

 private:
  struct Proj;
  std::unique_ptr<Proj> proj_;
  int utm_epsg_ = 0;
  Eigen::Vector2d origin_utm_m_ = Eigen::Vector2d::Zero();
};

}  // namespace msislab::io
