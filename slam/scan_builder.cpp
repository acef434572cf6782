#include "slam/scan_builder.hpp"

#include <cmath>

namespace msislab {

ScanPoint reading_in_vehicle(const SonarReading& reading,
                             const Eigen::Vector2d& p_vehicle_sonar_m) {
  const Eigen::Vector2d direction(std::cos(reading.bearing_vehicle_rad),
                                  std::sin(reading.bearing_vehicle_rad));
  Eigen::Matrix2d R;
  R << direction.x(), -direction.y(), direction.y(), direction.x();
  const double sigma_across_m = reading.range_m * reading.sigma_bearing_rad;
  ScanPoint point;
  point.p_m = p_vehicle_sonar_m + reading.range_m * direction;
  point.cov = R *
              Eigen::Vector2d(reading.sigma_range_m * reading.sigma_range_m,
                              sigma_across_m * sigma_across_m)
                  .asDiagonal() *
              R.transpose();
  point.t_s = reading.t_s;
  point.p_vehicle_m = point.p_m;
  return point;
}

void add_scan_points(const std::vector<SonarReading>& readings, const GaussianPose2& x_centre_beam,
                     const Eigen::Vector2d& p_vehicle_sonar_m, std::vector<ScanPoint>& points) {
  for (const SonarReading& reading : readings) {
    const ScanPoint in_vehicle = reading_in_vehicle(reading, p_vehicle_sonar_m);
    Matrix23d J_pose;
    Eigen::Matrix2d J_point;
    ScanPoint point;
    point.t_s = in_vehicle.t_s;
    point.p_vehicle_m = in_vehicle.p_m;
    point.p_m = x_centre_beam.mean.transform(in_vehicle.p_m, &J_pose, &J_point);
    point.cov = J_pose * x_centre_beam.cov * J_pose.transpose() +
                J_point * in_vehicle.cov * J_point.transpose();
    points.push_back(point);
  }
}

ScanBuilder::ScanBuilder(const ScanBuilderConfig& config) : config_(config) {}

std::optional<Scan> ScanBuilder::add_beam(double t_s,
                                          const GaussianPose2& motion_since_previous_beam,
                                          const std::vector<SonarReading>& readings) {
  beams_.push_back({t_s, motion_since_previous_beam, readings});
  if (static_cast<int>(beams_.size()) < config_.beams_per_scan) return std::nullopt;
  Scan scan = build();
  beams_.clear();
  return scan;
}

Scan ScanBuilder::build() {
  const std::size_t centre = beams_.size() / 2;
  // x_centre_i: the pose of beam i in the centre's frame. Later beams compose the motions
  // forward, x_ci = d_{c+1} (+) ... (+) d_i; earlier ones invert the chain back to the centre,
  // x_ci = (-)(d_{i+1} (+) ... (+) d_c).
  std::vector<GaussianPose2> x_centre(beams_.size());
  for (std::size_t i = centre + 1; i < beams_.size(); ++i) {
    x_centre[i] = compose(x_centre[i - 1], beams_[i].motion);
  }
  GaussianPose2 x_i_centre;  // x_ic, built from the centre backwards
  for (std::size_t i = centre; i-- > 0;) {
    x_i_centre = compose(beams_[i + 1].motion, x_i_centre);
    x_centre[i] = invert(x_i_centre);
  }

  Scan scan;
  scan.t_s = beams_[centre].t_s;
  scan.beams = beams_.size();
  for (std::size_t i = 0; i < beams_.size(); ++i) {
    add_scan_points(beams_[i].readings, x_centre[i], config_.p_vehicle_sonar_m, scan.points);
  }

  // Motion between scan frames: from the last centre to the end of its revolution, then through
  // this revolution's first beams (the first beam's motion links the two revolutions) to its
  // centre.
  GaussianPose2 to_centre = first_scan_ ? GaussianPose2{} : after_last_centre_;
  for (std::size_t i = first_scan_ ? 1 : 0; i <= centre; ++i) {
    to_centre = compose(to_centre, beams_[i].motion);
  }
  scan.motion = to_centre;
  after_last_centre_ = GaussianPose2{};
  for (std::size_t i = centre + 1; i < beams_.size(); ++i) {
    after_last_centre_ = compose(after_last_centre_, beams_[i].motion);
  }
  first_scan_ = false;
  return scan;
}

}  // namespace msislab
