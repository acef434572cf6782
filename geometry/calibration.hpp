// Sensor mounts and the local world frame of a dataset: the plain struct behind calibration.yaml.
// Defaults are the St. Pere calibration verified against GPS (../shared/datasets/stpere/README.md).
#pragma once

#include <Eigen/Core>
#include <cmath>

namespace msislab {

/// Heading unit (MRU/MTi): vehicle yaw psi = pi/2 - (yaw_mru - yaw_offset), in radians, less
/// the compass's one-cycle deviation d(psi) = a cos(psi) + b sin(psi) degrees (hard iron: the
/// reading points d(psi) counter-clockwise of the true vehicle yaw psi).
struct MruMount {
  double yaw_offset_deg = 86.0;    ///< MTi yaw reading when the vehicle points north, deg
  double deviation_cos_deg = 0.0;  ///< a, deg
  double deviation_sin_deg = 0.0;  ///< b, deg
};

/// DVL: bottom velocity in the vehicle frame = Rz(yaw) [vx, vy]_dvl / scale_factor, measured at
/// [x, y].
struct DvlMount {
  double yaw_deg = 293.5;  ///< rotation from the DVL frame to the vehicle frame, deg
  /// The DVL frame's y axis points to starboard of its x (a unit whose z points down, as most
  /// DVLs' x forward, y starboard, z down): its readings' y is mirrored before the rotation.
  /// false: to port, as the vehicle frame's (x forward, y port, z up).
  bool y_to_starboard = false;
  double x_m = 0.0;  ///< lever arm, vehicle frame, m
  double y_m = 0.0;  ///< lever arm, vehicle frame, m
  /// The DVL reports this many times the true velocity; the pipeline divides by it.
  double scale_factor = 1.0;
};

/// Sonar head: bearing in the vehicle frame = bearing_offset + bearing_sign x transducer angle.
struct SonarMount {
  double x_m = 0.33;                 ///< head position, vehicle frame, m
  double y_m = 0.0;                  ///< head position, vehicle frame, m
  double z_m = 0.0;                  ///< head height above the vehicle origin, m
  double bearing_offset_rad = M_PI;  ///< vehicle bearing of transducer angle 0, rad
  double bearing_sign = -1.0;        ///< +1 or -1 (the St. Pere head is mounted reversed)
  /// Added to the sonar log's beam times to put them on the navigation logs' clock, s. St. Pere:
  /// the beams' yaw, as scan matching sees it between consecutive scans, lags the MTi's by this
  /// much (estimated from the sensors alone, docs/simulator.md "Sonar clock offset").
  double time_offset_s = 0.66;
  /// The sonar reports ranges this many times the true ones (its sound speed over the water's);
  /// the pipeline divides every range by it.
  double range_scale = 1.0;
};

/// The local world frame: x East, y North in metres of UTM (zone from the origin's longitude),
/// relative to the origin. The St. Pere default origin is the first GPS fix of the dataset.
struct LocalFrame {
  double origin_latitude_deg = 42.0 + 12.225 / 60.0;
  double origin_longitude_deg = 3.0 + 6.2832 / 60.0;
};

struct Calibration {
  MruMount mru;
  DvlMount dvl;
  SonarMount sonar;
  LocalFrame frame;
};

/// Vehicle yaw (rad, counter-clockwise from East) from an MRU yaw reading (deg, clockwise), the
/// deviation removed (psi_read = psi + d(psi) solved for psi by fixed-point iteration).
double vehicle_yaw_from_mru(double yaw_mru_deg, const MruMount& mount);

/// MRU yaw reading (deg, in (-180, 180]) that the mount reports for a vehicle yaw, its deviation
/// included: the inverse of vehicle_yaw_from_mru.
double mru_yaw_from_vehicle(double yaw_vehicle_rad, const MruMount& mount);

/// Rotation from the DVL frame to the vehicle frame.
Eigen::Matrix2d R_vehicle_dvl(const DvlMount& mount);

/// Bearing of a sonar beam in the vehicle frame from the transducer angle.
double sonar_bearing_in_vehicle(double transducer_angle_rad, const SonarMount& mount);

}  // namespace msislab
