#include "slam/scan_sequence.hpp"

#include <Eigen/Cholesky>
#include <algorithm>
#include <cmath>

namespace msislab {

namespace {

/// A square root L (L L^T = P) of a motion covariance, zero when it is not positive definite.
Eigen::Matrix3d square_root(const Eigen::Matrix3d& P) {
  const Eigen::LLT<Eigen::Matrix3d> llt(P);
  if (llt.info() != Eigen::Success) return Eigen::Matrix3d::Zero();
  return llt.matrixL();
}

/// The revolution of beams [begin, begin + n) (its odometry samples at the same indices), in
/// the frame of its central beam c. Beam poses in that frame: means from the filtered poses;
/// covariances exact after the centre (the key clone marked at c), and mirrored before it, the
/// motion over t_c - t_i having about the covariance of the one over t_i' - t_c with i' = 2c - i
/// (a stationary constant-velocity model is symmetric in time). i' < c + n, the next key.
PlacedScan build_scan(std::vector<BeamReadings>::const_iterator beams,
                      const std::vector<OdometrySample>& odometry, std::size_t begin, std::size_t n,
                      const Eigen::Vector2d& p_vehicle_sonar_m) {
  const std::size_t centre = begin + n / 2;
  const Pose2& x_centre = odometry[centre].pose.pose.mean;
  PlacedScan placed;
  placed.scan.t_s = odometry[centre].t_s;
  placed.scan.beams = n;
  placed.scan.motion = odometry[centre].motion_since_key;
  placed.centre_world = odometry[centre].pose;
  // The velocity the revolution moved at: the dead-reckoning motion from its first beam to its
  // last, over its time. A clock offset moves every beam by tau times the velocity at its own
  // time, so the scan as a whole moves by tau times their mean, not the centre's (in a turn that
  // fills part of a revolution the two differ, and regressed on the centre's the offset came out
  // about half of the truth on the marina loop).
  const std::size_t before = begin;
  const std::size_t after = begin + n - 1;
  const double span_s = odometry[after].t_s - odometry[before].t_s;
  if (span_s > 0.0) {
    placed.scan.velocity_vehicle =
        odometry[before].pose.pose.mean.between(odometry[after].pose.pose.mean).vector() / span_s;
  }
  // The shared error of each half (docs/scan_matching.md): a beam's pose error is taken as
  // f_i L xi_side, with L L^T the motion covariance over the whole half and f_i^2 =
  // tr(P_i) / tr(P_half) the beam's share of it, so the marginal matches its own clone's size.
  const std::size_t last = begin + n - 1;
  const std::size_t mirror_of_first = std::min(2 * centre - begin, odometry.size() - 1);
  const Eigen::Matrix3d& P_after = odometry[last].motion_since_key.cov;
  const Eigen::Matrix3d& P_before = odometry[mirror_of_first].motion_since_key.cov;
  const Eigen::Matrix3d L_after = square_root(P_after), L_before = square_root(P_before);
  for (std::size_t i = begin; i < begin + n; ++i) {
    GaussianPose2 x_centre_beam;
    x_centre_beam.mean = x_centre.between(odometry[i].pose.pose.mean);
    if (i > centre) {
      x_centre_beam.cov = odometry[i].motion_since_key.cov;
    } else if (i < centre) {
      // The mirror may lie past this revolution: every sample up to the next centre still
      // measures from this centre's clone. Only the end of the data clamps it.
      x_centre_beam.cov =
          odometry[std::min(2 * centre - i, odometry.size() - 1)].motion_since_key.cov;
    }
    BeamDistortion distortion;
    distortion.side = i >= centre ? 1 : 0;
    const Eigen::Matrix3d& P_half = i >= centre ? P_after : P_before;
    if (P_half.trace() > 0.0) {
      distortion.loading = std::sqrt(std::min(1.0, x_centre_beam.cov.trace() / P_half.trace())) *
                           (i >= centre ? L_after : L_before);
    }
    add_scan_points((beams + static_cast<long>(i - begin))->readings, x_centre_beam,
                    p_vehicle_sonar_m, placed.scan.points, distortion);
  }
  return placed;
}

}  // namespace

std::vector<PlacedScan> build_scans(const std::vector<BeamReadings>& beams,
                                    const NavigationLog& navigation,
                                    const DeadReckoningConfig& dead_reckoning,
                                    const Eigen::Vector2d& p_vehicle_dvl_m,
                                    const StampedPose& initial, const ScanConfig& config) {
  const auto first = std::find_if(beams.begin(), beams.end(),
                                  [&](const BeamReadings& b) { return b.t_s >= initial.t_s; });
  std::vector<double> times_s;
  for (auto it = first; it != beams.end(); ++it) times_s.push_back(it->t_s);
  // The scan centres are keys: their motions come from one clone each, exactly (composing the
  // per-beam increments as independent would be overconfident: they share the EKF's velocity
  // error; docs/scan_matching.md, "Status, measured", has the measured effect).
  const std::size_t per_scan = static_cast<std::size_t>(config.beams_per_scan);
  const std::vector<OdometrySample> odometry =
      odometry_at(navigation, dead_reckoning, p_vehicle_dvl_m, initial, times_s,
                  KeySamples{per_scan / 2, per_scan});

  std::vector<PlacedScan> scans;
  for (std::size_t begin = 0; begin + per_scan <= odometry.size(); begin += per_scan) {
    scans.push_back(build_scan(first + static_cast<long>(begin), odometry, begin, per_scan,
                               config.p_vehicle_sonar_m));
    Scan& scan = scans.back().scan;
    if (!navigation.heading.empty()) {
      const HeadingReading& heading = nearest_heading(navigation.heading, scan.t_s);
      if (std::abs(heading.t_s - scan.t_s) <= config.max_compass_gap_s) {
        scan.compass_yaw_world_rad = heading.yaw_rad;
        scan.compass_sigma_rad = dead_reckoning.heading_sigma_rad;
      }
    }
  }
  return scans;
}

std::vector<Eigen::Vector2d> world_points(const std::vector<PlacedScan>& scans) {
  std::vector<Eigen::Vector2d> points;
  for (const PlacedScan& s : scans) {
    for (const ScanPoint& p : s.scan.points) {
      points.push_back(s.centre_world.pose.mean.transform(p.p_m));
    }
  }
  return points;
}

}  // namespace msislab
