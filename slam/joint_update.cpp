// The joint update of a step's matches (paper Eq. 8; docs/trajectory_slam.md, "Joint update"):
// TrajectorySlam::update_jointly and its steps. Every match is made from the step's prediction,
// the matches are stacked with their cross-covariances, and the largest jointly compatible set of
// them updates the state at once.
#include <Eigen/Cholesky>
#include <algorithm>
#include <cstdint>
#include <limits>

#include "slam/trajectory_slam.hpp"

namespace msislab {

namespace {

/// A step's observations stacked (paper Eq. 8) with their covariance R_all; observation i takes
/// the rows [offset[i], offset[i + 1]).
struct StackedObservations {
  std::vector<RelativePoseObservation> observations;
  Eigen::MatrixXd R_all;
  std::vector<Eigen::Index> offset;

  /// z and R of a set of the observations.
  void select(const std::vector<std::size_t>& set, std::vector<RelativePoseObservation>& z,
              Eigen::MatrixXd& R) const {
    z.clear();
    std::vector<Eigen::Index> rows;
    for (const std::size_t i : set) {
      z.push_back(observations[i]);
      for (Eigen::Index r = offset[i]; r < offset[i + 1]; ++r) rows.push_back(r);
    }
    R = R_all(rows, rows);
  }
};

/// The stacked covariance of the observations, matches[used[i]] giving observation i:
/// A_i cov(z_i, z_j) A_j^T, cov(z_i, z_i) = noise[i] (spIC's own, or its part not in the state),
/// between two matches the errors of the newest scan they share (docs/trajectory_slam.md, "Joint
/// update"; its points' alone with halves_in_state), or zero without cross_covariance.
void stack_covariance(const std::vector<ValidatedMatch>& matches,
                      const std::vector<std::size_t>& used,
                      const std::vector<Eigen::Matrix3d>& noise, bool cross_covariance,
                      bool halves_in_state, const std::vector<ScanPoint>& newest_points,
                      StackedObservations& stacked) {
  const std::size_t n = used.size();
  std::vector<Eigen::Index>& offset = stacked.offset;
  offset.assign(n + 1, 0);
  for (std::size_t i = 0; i < n; ++i) {
    offset[i + 1] = offset[i] + stacked.observations[i].observed.rows();
  }
  stacked.R_all = Eigen::MatrixXd::Zero(offset[n], offset[n]);
  for (std::size_t i = 0; i < n; ++i) {
    const ValidatedMatch& mi = matches[used[i]];
    for (std::size_t j = i; j < n; ++j) {
      const ValidatedMatch& mj = matches[used[j]];
      Eigen::Matrix3d C = noise[i];
      if (j != i) {
        C = Eigen::Matrix3d::Zero();
        if (cross_covariance) C = shared_current_covariance(mi.match, mj.match, newest_points);
        if (cross_covariance && halves_in_state) {
          // The half-scans' errors are the state's: only the points' noise is shared here.
          for (std::size_t side = 0; side < 2; ++side) {
            C -= mi.match.current_loading.half[side] *
                 mj.match.current_loading.half[side].transpose();
          }
        }
      }
      const Eigen::MatrixXd block = mi.observed * C * mj.observed.transpose();
      stacked.R_all.block(offset[i], offset[j], block.rows(), block.cols()) = block;
      stacked.R_all.block(offset[j], offset[i], block.cols(), block.rows()) = block.transpose();
    }
  }
}

/// Joint compatibility (JCBB-style): the largest set of the observations whose stack agrees with
/// the prediction at the gate's probability, the lowest NIS among sets of that size. Up to
/// kExhaustive observations every subset is tried; beyond, the one of largest NIS of its own
/// (`own`) leaves until the rest agree. compatible(set, &nis): whether a set agrees, and its NIS.
template <class Compatible>
std::vector<std::size_t> jointly_compatible(const std::vector<double>& own,
                                            const Compatible& compatible) {
  const std::size_t n = own.size();
  constexpr std::size_t kExhaustive = 8;
  std::vector<std::size_t> chosen;
  if (n <= kExhaustive) {
    double best = std::numeric_limits<double>::infinity();
    for (std::uint32_t mask = 1; mask < (1u << n); ++mask) {
      std::vector<std::size_t> set;
      for (std::size_t i = 0; i < n; ++i) {
        if (mask >> i & 1u) set.push_back(i);
      }
      double nis = 0.0;
      if (set.size() < chosen.size() || !compatible(set, &nis)) continue;
      if (set.size() > chosen.size() || nis < best) chosen = set, best = nis;
    }
  } else {
    std::vector<std::size_t> set(n);
    for (std::size_t i = 0; i < n; ++i) set[i] = i;
    double nis = 0.0;
    while (!set.empty() && !compatible(set, &nis)) {
      set.erase(std::max_element(set.begin(), set.end(),
                                 [&](std::size_t a, std::size_t b) { return own[a] < own[b]; }));
    }
    chosen = set;
  }
  return chosen;
}

}  // namespace

void TrajectorySlam::update_jointly(std::size_t k, const std::vector<std::size_t>& candidates,
                                    SlamStepStats& stats) {
  // Every match from the prediction: Eq. 8 stacks them before any update.
  std::vector<ValidatedMatch> matches;
  std::vector<GaussianPose2> predictions(candidates.size());
  StackedObservations stacked;
  std::vector<std::size_t> used;       // indices into matches of the observations
  std::vector<Eigen::Matrix3d> noise;  // each one's R
  for (std::size_t c = 0; c < candidates.size(); ++c) {
    ValidatedMatch m = match(candidates[c], k, predictions[c]);
    if (m.match.valid) ++stats.matched;
    if (m.rejection == MatchRejection::kNone) {
      used.push_back(c);
      stacked.observations.push_back({candidates[c], m.match.estimate.mean, m.observed, {}});
      // With the scans' shared errors in the state, a match's noise is its own part, and what
      // the step's matches share is in the state.
      noise.push_back(match_noise(candidates[c], k, m.match, &stacked.observations.back().shared));
    }
    matches.push_back(std::move(m));
  }
  // With the points' rigid errors in the state too, the step's matches share nothing beyond it.
  const ScanSharedErrors held = config_.filter.scan_shared_errors;
  stack_covariance(
      matches, used, noise,
      config_.filter.match_cross_covariance && held != ScanSharedErrors::kMotionAndPoints,
      held == ScanSharedErrors::kMotion, points_[k], stacked);
  const std::size_t n = used.size();
  std::vector<RelativePoseObservation> z;
  Eigen::MatrixXd R;
  const auto compatible = [&](const std::vector<std::size_t>& set, double* nis) {
    stacked.select(set, z, R);
    *nis = innovation_nis(k, z, R);
    return *nis <= gate_for_dimensions(config_.front_end.innovation_gate_chi2, R.rows());
  };
  // Each match's own NIS against the prediction: the greedy search of jointly_compatible drops
  // the largest first, and matches.csv reports it.
  std::vector<double> own(n);
  for (std::size_t i = 0; i < n; ++i) compatible({i}, &own[i]);
  const std::vector<std::size_t> chosen = jointly_compatible(own, compatible);
  std::vector<bool> accepted(n, false);
  if (!chosen.empty()) {
    stacked.select(chosen, z, R);
    if (const std::optional<std::size_t> window = update_relative_poses(k, z, R)) {
      stats.note_window(*window);
      for (const std::size_t i : chosen) accepted[i] = true;
      stats.accepted += static_cast<int>(chosen.size());
    }
  }
  std::vector<double> own_nis(matches.size(), std::numeric_limits<double>::quiet_NaN());
  for (std::size_t i = 0; i < n; ++i) {
    if (!accepted[i]) matches[used[i]].rejection = MatchRejection::kInnovation;
    own_nis[used[i]] = own[i];
  }
  for (std::size_t c = 0; c < matches.size(); ++c) {
    stats.matches.push_back(record_of(candidates[c], k, matches[c], predictions[c], own_nis[c]));
    stats.rejections.count(matches[c]);
    totals_.rejections.count(matches[c]);
  }
}

}  // namespace msislab
