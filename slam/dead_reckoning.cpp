#include "slam/dead_reckoning.hpp"

#include <Eigen/LU>
#include <algorithm>
#include <cmath>
#include <limits>

#include "geometry/se2.hpp"
#include "slam/numerical_error.hpp"

namespace msislab {

DeadReckoningEkf::DeadReckoningEkf(const DeadReckoningConfig& config,
                                   const Eigen::Vector2d& p_vehicle_dvl_m,
                                   const StampedPose& initial)
    : config_(config), p_vehicle_dvl_m_(p_vehicle_dvl_m), t_s_(initial.t_s) {
  x_.head<3>() = initial.pose.mean.vector();
  p_start_world_m_ = initial.pose.mean.translation();
  P_.topLeftCorner<3, 3>() = initial.pose.cov;
  const double sv2 = config.initial_velocity_sigma_mps * config.initial_velocity_sigma_mps;
  const double sr2 = config.initial_yaw_rate_sigma_radps * config.initial_yaw_rate_sigma_radps;
  const double sb = config.heading_bias_sigma_deg * M_PI / 180.0;
  P_.diagonal().tail<4>() << sv2, sv2, sr2, sb * sb;
  for (int slot = 0; slot < kCloneSlots; ++slot) mark(slot);
}

void DeadReckoningEkf::predict(double t_s) {
  const double dt = t_s - t_s_;
  if (!(dt > 0.0)) return;
  const double yaw = x_(2), u = x_(3), v = x_(4), r = x_(5);
  const double c = std::cos(yaw), s = std::sin(yaw);
  // x+ = x + R(yaw) [u v]^T dt, yaw+ = yaw + r dt, [u v r] constant (Ribas 2008, Sec. 3.1);
  // the heading bias beta+ = beta + a random walk.
  DeadReckoningMatrix F = DeadReckoningMatrix::Identity();
  F(0, 2) = -(u * s + v * c) * dt;
  F(1, 2) = (u * c - v * s) * dt;
  F(0, 3) = c * dt;
  F(0, 4) = -s * dt;
  F(1, 3) = s * dt;
  F(1, 4) = c * dt;
  F(2, 5) = dt;
  x_(0) += (u * c - v * s) * dt;
  x_(1) += (u * s + v * c) * dt;
  x_(2) = normalize_angle(yaw + r * dt);

  // Continuous white acceleration noise, integrated exactly over dt: per axis q [dt^3/3, dt^2/2;
  // dt^2/2, dt]. The surge/sway noise is isotropic, so the world-frame position block stays q I
  // and the position-velocity block is q dt^2/2 R(yaw).
  const double qa = config_.accel_sigma_mps2 * config_.accel_sigma_mps2;
  const double qr = config_.yaw_accel_sigma_radps2 * config_.yaw_accel_sigma_radps2;
  const double dt2 = dt * dt, dt3 = dt2 * dt;
  DeadReckoningMatrix Q = DeadReckoningMatrix::Zero();
  Q.block<2, 2>(0, 0) = qa * dt3 / 3.0 * Eigen::Matrix2d::Identity();
  Q.block<2, 2>(0, 3) = qa * dt2 / 2.0 * Pose2(0.0, 0.0, yaw).rotation();
  Q.block<2, 2>(3, 0) = Q.block<2, 2>(0, 3).transpose();
  Q.block<2, 2>(3, 3) = qa * dt * Eigen::Matrix2d::Identity();
  Q(2, 2) = qr * dt3 / 3.0;
  Q(2, 5) = Q(5, 2) = qr * dt2 / 2.0;
  Q(5, 5) = qr * dt;
  const double walk = config_.heading_bias_walk_deg_per_sqrt_s * M_PI / 180.0;
  Q(6, 6) = walk * walk * dt;
  P_ = F * P_ * F.transpose() + Q;
  for (Clone& clone : clones_) clone.P_x = F * clone.P_x;  // the clones do not move
  t_s_ = t_s;
}

template <int M>
double DeadReckoningEkf::update(const Eigen::Matrix<double, M, 1>& innovation,
                                const Eigen::Matrix<double, M, kDeadReckoningStates>& H,
                                const Eigen::Matrix<double, M, M>& R, double gate_chi2) {
  // S = H P H^T + R; NIS = nu^T S^-1 nu; K = P H^T S^-1 (M <= 2: closed-form inverse).
  const Eigen::Matrix<double, M, M> S_inv = (H * P_ * H.transpose() + R).inverse();
  const double nis = innovation.dot(S_inv * innovation);
  if (gate_chi2 > 0.0 && nis > gate_chi2) return nis;
  const Eigen::Matrix<double, kDeadReckoningStates, M> K = P_ * H.transpose() * S_inv;
  // The clones keep the estimate made at their mark (frozen, not smoothed): only the correlation
  // of the state's error with theirs changes, e+ = (I - K H) e - K v.
  for (Clone& clone : clones_) clone.P_x -= K * H * clone.P_x;
  x_ += K * innovation;
  x_(2) = normalize_angle(x_(2));
  // Joseph form keeps P symmetric and positive definite.
  const DeadReckoningMatrix I_KH = DeadReckoningMatrix::Identity() - K * H;
  P_ = I_KH * P_ * I_KH.transpose() + K * R * K.transpose();
  return nis;
}

double DeadReckoningEkf::update_dvl(const DvlVelocity& dvl) {
  predict(dvl.t_s);
  // z = [u - r y_dvl, v + r x_dvl]: the vehicle velocity seen at the DVL's lever arm.
  Eigen::Matrix<double, 2, kDeadReckoningStates> H =
      Eigen::Matrix<double, 2, kDeadReckoningStates>::Zero();
  H(0, 3) = 1.0;
  H(0, 5) = -p_vehicle_dvl_m_.y();
  H(1, 4) = 1.0;
  H(1, 5) = p_vehicle_dvl_m_.x();
  const Eigen::Vector2d innovation = dvl.v_vehicle_mps - H * x_;
  const Eigen::Matrix2d R =
      config_.dvl_sigma_mps * config_.dvl_sigma_mps * Eigen::Matrix2d::Identity();
  return update<2>(innovation, H, R, config_.dvl_gate_chi2);
}

double DeadReckoningEkf::update_heading(const HeadingReading& heading) {
  predict(heading.t_s);
  // z = yaw + beta: the reading's bias (zero, and known, when it does not walk).
  Eigen::Matrix<double, 1, kDeadReckoningStates> H =
      Eigen::Matrix<double, 1, kDeadReckoningStates>::Zero();
  H(0, 2) = 1.0;
  H(0, 6) = 1.0;
  const Eigen::Matrix<double, 1, 1> innovation(normalize_angle(heading.yaw_rad - x_(2) - x_(6)));
  const Eigen::Matrix<double, 1, 1> R(config_.heading_sigma_rad * config_.heading_sigma_rad);
  return update<1>(innovation, H, R, 0.0);
}

void DeadReckoningEkf::mark(int slot) {
  Clone& clone = clones_[slot];
  clone.pose = x_.head<3>();
  clone.P = P_.topLeftCorner<3, 3>();
  clone.P_x = P_.leftCols<3>();
}

GaussianPose2 DeadReckoningEkf::motion_since_mark(int slot) const {
  const Clone& clone = clones_[slot];
  Eigen::Matrix3d J_mark;
  Eigen::Matrix3d J_now;
  GaussianPose2 motion;
  motion.mean = Pose2(clone.pose).between(Pose2(x_.head<3>()), &J_mark, &J_now);
  const Eigen::Matrix3d P_now_mark = clone.P_x.topRows<3>();
  const Eigen::Matrix3d cross = J_now * P_now_mark * J_mark.transpose();
  motion.cov = J_mark * clone.P * J_mark.transpose() +
               J_now * P_.topLeftCorner<3, 3>() * J_now.transpose() + cross + cross.transpose();
  // The DVL scale's error moves the motion's translation by (k - 1) t (t the motion's own).
  if (config_.dvl_scale_sigma > 0.0) {
    const Eigen::Vector2d t = motion.mean.translation();
    motion.cov.topLeftCorner<2, 2>() +=
        config_.dvl_scale_sigma * config_.dvl_scale_sigma * t * t.transpose();
  }
  return motion;
}

StampedPose DeadReckoningEkf::pose() const {
  StampedPose out;
  out.t_s = t_s_;
  out.pose.mean = Pose2(x_(0), x_(1), x_(2));
  out.pose.cov = P_.topLeftCorner<3, 3>();
  // The DVL scale's error moves the position by (k - 1) times the distance dead-reckoned.
  if (config_.dvl_scale_sigma > 0.0) {
    const Eigen::Vector2d d = x_.head<2>() - p_start_world_m_;
    out.pose.cov.topLeftCorner<2, 2>() +=
        config_.dvl_scale_sigma * config_.dvl_scale_sigma * d * d.transpose();
  }
  return out;
}

namespace {

/// A navigation log's measurements fed to an EKF in time order (DVL first on equal times), those
/// before the start skipped. After each update, on_dvl(nis) or on_heading(nis) is called.
class MeasurementFeed {
 public:
  MeasurementFeed(const NavigationLog& log, double t_start_s) : log_(log), t_start_s_(t_start_s) {}

  template <typename OnDvl, typename OnHeading>
  void run_until(double t_end_s, DeadReckoningEkf& ekf, OnDvl on_dvl, OnHeading on_heading) {
    while (true) {
      const bool dvl = i_dvl_ < log_.dvl.size() && log_.dvl[i_dvl_].t_s <= t_end_s;
      const bool heading =
          i_heading_ < log_.heading.size() && log_.heading[i_heading_].t_s <= t_end_s;
      if (!dvl && !heading) return;
      if (dvl && (!heading || log_.dvl[i_dvl_].t_s <= log_.heading[i_heading_].t_s)) {
        const DvlVelocity& m = log_.dvl[i_dvl_++];
        if (m.t_s >= t_start_s_) on_dvl(ekf.update_dvl(m));
      } else {
        const HeadingReading& m = log_.heading[i_heading_++];
        if (m.t_s >= t_start_s_) on_heading(ekf.update_heading(m));
      }
    }
  }

 private:
  const NavigationLog& log_;
  double t_start_s_;
  std::size_t i_dvl_ = 0, i_heading_ = 0;
};

}  // namespace

DeadReckoningResult run_dead_reckoning(const NavigationLog& log, const DeadReckoningConfig& config,
                                       const Eigen::Vector2d& p_vehicle_dvl_m,
                                       const StampedPose& initial) {
  DeadReckoningResult result;
  DeadReckoningEkf ekf(config, p_vehicle_dvl_m, initial);
  result.trajectory.push_back(ekf.pose());
  auto record = [&] {
    if (ekf.time() <= result.trajectory.back().t_s) return;
    const StampedPose& pose = ekf.pose();
    require_finite(pose.pose.mean.vector().allFinite() && pose.pose.cov.allFinite(),
                   "dead reckoning", result.trajectory.size(), pose.t_s, "DVL or heading update",
                   "pose");
    result.trajectory.push_back(pose);
  };
  MeasurementFeed(log, initial.t_s)
      .run_until(
          std::numeric_limits<double>::infinity(), ekf,
          [&](double nis) {
            if (config.dvl_gate_chi2 > 0.0 && nis > config.dvl_gate_chi2) {
              ++result.dvl_rejected;
            } else {
              ++result.dvl_used;
              result.dvl_mean_nis += nis;
            }
            record();
          },
          [&](double nis) {
            result.heading_mean_nis += nis;
            ++result.heading_used;
            record();
          });
  if (result.dvl_used) result.dvl_mean_nis /= result.dvl_used;
  if (result.heading_used) result.heading_mean_nis /= result.heading_used;
  return result;
}

}  // namespace msislab

namespace msislab {

std::vector<OdometrySample> odometry_at(const NavigationLog& log, const DeadReckoningConfig& config,
                                        const Eigen::Vector2d& p_vehicle_dvl_m,
                                        const StampedPose& initial,
                                        const std::vector<double>& times_s,
                                        const KeySamples& keys) {
  constexpr int kBeamSlot = 0, kKeySlot = 1;
  DeadReckoningEkf ekf(config, p_vehicle_dvl_m, initial);
  MeasurementFeed feed(log, initial.t_s);
  std::vector<OdometrySample> samples;
  samples.reserve(times_s.size());
  for (const double t_s : times_s) {
    feed.run_until(
        t_s, ekf, [](double) {}, [](double) {});
    ekf.predict(t_s);
    const bool is_key = keys.is_key(samples.size());
    samples.push_back({t_s, ekf.motion_since_mark(kBeamSlot), ekf.pose(),
                       ekf.motion_since_mark(kKeySlot), is_key});
    ekf.mark(kBeamSlot);
    if (is_key) ekf.mark(kKeySlot);
  }
  return samples;
}

std::vector<StampedPose> integrate_velocities(const NavigationLog& log,
                                              const StampedPose& initial) {
  std::vector<StampedPose> trajectory = {initial};
  if (log.heading.empty()) return trajectory;
  Eigen::Vector2d p_world_m = initial.pose.mean.translation();
  for (std::size_t i = 0; i + 1 < log.dvl.size(); ++i) {
    const double t0 = std::max(log.dvl[i].t_s, initial.t_s);
    const double t1 = log.dvl[i + 1].t_s;
    if (t1 <= t0) continue;
    const double yaw = nearest_heading(log.heading, t0).yaw_rad;
    p_world_m += Pose2(0.0, 0.0, yaw).rotation() * log.dvl[i].v_vehicle_mps * (t1 - t0);
    StampedPose pose;
    pose.t_s = t1;
    pose.pose.mean = Pose2(p_world_m.x(), p_world_m.y(), nearest_heading(log.heading, t1).yaw_rad);
    trajectory.push_back(pose);
  }
  return trajectory;
}

}  // namespace msislab
