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
  point.cov_reading = point.cov;
  point.t_s = reading.t_s;
  point.p_vehicle_m = point.p_m;
  point.p_sonar_m = p_vehicle_sonar_m;
  point.p_vehicle_sonar_m = p_vehicle_sonar_m;
  return point;
}

void add_scan_points(const std::vector<SonarReading>& readings, const GaussianPose2& x_centre_beam,
                     const Eigen::Vector2d& p_vehicle_sonar_m, std::vector<ScanPoint>& points,
                     const BeamDistortion& distortion) {
  for (const SonarReading& reading : readings) {
    const ScanPoint in_vehicle = reading_in_vehicle(reading, p_vehicle_sonar_m);
    Matrix23d J_pose;
    Eigen::Matrix2d J_point;
    ScanPoint point;
    point.t_s = in_vehicle.t_s;
    point.p_vehicle_m = in_vehicle.p_m;
    point.p_m = x_centre_beam.mean.transform(in_vehicle.p_m, &J_pose, &J_point);
    point.p_vehicle_sonar_m = p_vehicle_sonar_m;
    point.p_sonar_m = x_centre_beam.mean.transform(p_vehicle_sonar_m);
    point.cov_reading = J_point * in_vehicle.cov * J_point.transpose();
    point.cov = J_pose * x_centre_beam.cov * J_pose.transpose() + point.cov_reading;
    point.distortion = J_pose * distortion.loading;
    point.side = distortion.side;
    points.push_back(point);
  }
}

}  // namespace msislab
