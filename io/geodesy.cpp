#include "io/geodesy.hpp"

#include <proj.h>

#include <cmath>
#include <string>

#include "io/input_error.hpp"

namespace msislab::io {

struct LocalProjection::Proj {
  PJ_CONTEXT* context = nullptr;
  PJ* transform = nullptr;
  ~Proj() {
    if (transform) proj_destroy(transform);
    if (context) proj_context_destroy(context);
  }
};

namespace {
int utm_epsg_for(double latitude_deg, double longitude_deg) {
  const int zone = static_cast<int>(std::floor((longitude_deg + 180.0) / 6.0)) % 60 + 1;
  return (latitude_deg >= 0.0 ? 32600 : 32700) + zone;
}
}  // namespace

LocalProjection::LocalProjection(const LocalFrame& frame) : proj_(std::make_unique<Proj>()) {
  const std::string where = "local frame origin (" + std::to_string(frame.origin_latitude_deg) +
                            ", " + std::to_string(frame.origin_longitude_deg) + ")";
  if (!(std::abs(frame.origin_latitude_deg) <= 84.0) ||
      !(std::abs(frame.origin_longitude_deg) <= 180.0)) {
    throw InputError(where + ": outside the UTM latitude/longitude range");
  }
  // Plain 6-degree zones: the Norway/Svalbard exceptions do not matter for a local metric frame.
  utm_epsg_ = utm_epsg_for(frame.origin_latitude_deg, frame.origin_longitude_deg);
  proj_->context = proj_context_create();
  const std::string utm = "EPSG:" + std::to_string(utm_epsg_);
  PJ* raw = proj_create_crs_to_crs(proj_->context, "EPSG:4326", utm.c_str(), nullptr);
  if (raw) {
    // Axis order longitude, latitude / easting, northing, whatever the CRS definitions say.
    proj_->transform = proj_normalize_for_visualization(proj_->context, raw);
    proj_destroy(raw);
  }
  if (!proj_->transform) {
    const int err = proj_context_errno(proj_->context);
    throw InputError(where + ": PROJ cannot build WGS84 -> " + utm + ": " +
                     proj_context_errno_string(proj_->context, err));
  }
  const PJ_COORD o =
      proj_trans(proj_->transform, PJ_FWD,
                 proj_coord(frame.origin_longitude_deg, frame.origin_latitude_deg, 0, 0));
  origin_utm_m_ = {o.xy.x, o.xy.y};
}

LocalProjection::~LocalProjection() = default;

Eigen::Vector2d LocalProjection::to_local(double latitude_deg, double longitude_deg) const {
  const PJ_COORD c =
      proj_trans(proj_->transform, PJ_FWD, proj_coord(longitude_deg, latitude_deg, 0, 0));
  return Eigen::Vector2d(c.xy.x, c.xy.y) - origin_utm_m_;
}

std::pair<double, double> LocalProjection::to_geodetic(const Eigen::Vector2d& p_local_m) const {
  const Eigen::Vector2d utm = p_local_m + origin_utm_m_;
  const PJ_COORD c = proj_trans(proj_->transform, PJ_INV, proj_coord(utm.x(), utm.y(), 0, 0));
  return {c.lp.phi, c.lp.lam};
}

}  // namespace msislab::io
