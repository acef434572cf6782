#include "slam/scan_matching.hpp"

#include <Eigen/Cholesky>
#include <Eigen/LU>
#include <algorithm>
#include <cmath>
#include <limits>
#include <utility>

#include "slam/line_normals.hpp"

namespace msislab {

namespace {

struct Association {
  std::size_t current = 0;
  std::size_t reference = 0;
};

/// The largest eigenvalue of a symmetric 2 x 2 matrix.
double largest_eigenvalue(const Eigen::Matrix2d& m) {
  const double half_trace = 0.5 * (m(0, 0) + m(1, 1));
  const double half_diff = 0.5 * (m(0, 0) - m(1, 1));
  return half_trace + std::sqrt(half_diff * half_diff + m(0, 1) * m(1, 0));
}

/// d^T (C + R)^-1 d, written out as Eigen computes d.dot((C + R).inverse() * d) for a 2 x 2 (the
/// cofactors over the determinant, then the products in the same order): the same bits, without
/// the temporaries.
double mahalanobis2(const Eigen::Vector2d& d, const Eigen::Matrix2d& C, const Eigen::Matrix2d& R) {
  const double s00 = C(0, 0) + R(0, 0), s01 = C(0, 1) + R(0, 1);
  const double s10 = C(1, 0) + R(1, 0), s11 = C(1, 1) + R(1, 1);
  const double inverse_determinant = 1.0 / (s00 * s11 - s10 * s01);
  const double i00 = s11 * inverse_determinant, i01 = -s01 * inverse_determinant;
  const double i10 = -s10 * inverse_determinant, i11 = s00 * inverse_determinant;
  const double r0 = i00 * d(0) + i01 * d(1), r1 = i10 * d(0) + i11 * d(1);
  return d(0) * r0 + d(1) * r1;
}

/// E-step: each current point moved by the guess (covariance including the guess's) to its
/// nearest reference point in Mahalanobis distance, when within the gate; when `reciprocal`, only
/// the pairs whose current point is also the one nearest to their reference point.
std::vector<Association> associate(const std::vector<ScanPoint>& reference,
                                   const std::vector<ScanPoint>& current, const GaussianPose2& q,
                                   double gate_chi2, bool reciprocal) {
  std::vector<Association> pairs;
  std::vector<double> nearest_d2(reference.size(), std::numeric_limits<double>::infinity());
  std::vector<std::size_t> nearest_current(reference.size(), current.size());
  // A pair's Mahalanobis distance is at least |d|^2 / lambda_max(S), and lambda_max(S) is at most
  // lambda_max(C) + the largest lambda_max of the reference covariances: pairs further than that
  // bound allows are outside the gate and skipped unevaluated (the result is the same).
  double reference_lambda_max = 0.0;
  for (const ScanPoint& r : reference) {
    reference_lambda_max = std::max(reference_lambda_max, largest_eigenvalue(r.cov));
  }
  // The reference in order of x: a current point's candidates lie within its reach in x, a
  // window found by bisection (padded by a rounding margin; the test of |d|^2 stays exact). A
  // point whose x is not finite never passes that test: it is left out.
  std::vector<std::size_t> by_x;
  for (std::size_t i = 0; i < reference.size(); ++i) {
    if (std::isfinite(reference[i].p_m.x())) by_x.push_back(i);
  }
  std::sort(by_x.begin(), by_x.end(), [&](std::size_t a, std::size_t b) {
    return reference[a].p_m.x() < reference[b].p_m.x();
  });
  std::vector<double> x_sorted(by_x.size());
  for (std::size_t k = 0; k < by_x.size(); ++k) x_sorted[k] = reference[by_x[k]].p_m.x();
  for (std::size_t j = 0; j < current.size(); ++j) {
    Matrix23d J_q;
    Eigen::Matrix2d J_p;
    const Eigen::Vector2d moved = q.mean.transform(current[j].p_m, &J_q, &J_p);
    const Eigen::Matrix2d C =
        J_q * q.cov * J_q.transpose() + J_p * current[j].cov * J_p.transpose();
    const double reach2 = gate_chi2 * (largest_eigenvalue(C) + reference_lambda_max);
    const double reach_x = std::sqrt(reach2) * (1.0 + 1e-12) + 1e-12;
    const auto lo = std::lower_bound(x_sorted.begin(), x_sorted.end(), moved.x() - reach_x);
    const auto hi = std::upper_bound(lo, x_sorted.end(), moved.x() + reach_x);
    // The nearest in the gate; among equals the lowest index, as a pass in index order finds.
    double best = gate_chi2;
    std::size_t best_i = reference.size();
    for (auto k = lo; k != hi; ++k) {
      const std::size_t i = by_x[static_cast<std::size_t>(k - x_sorted.begin())];
      const Eigen::Vector2d d = moved - reference[i].p_m;
      if (d.squaredNorm() > reach2) continue;
      const double d2 = mahalanobis2(d, C, reference[i].cov);
      if (d2 < best || (d2 == best && best_i < reference.size() && i < best_i)) {
        best = d2, best_i = i;
      }
      if (d2 < nearest_d2[i]) nearest_d2[i] = d2, nearest_current[i] = j;
    }
    if (best_i < reference.size()) pairs.push_back({j, best_i});
  }
  if (!reciprocal) return pairs;
  std::vector<Association> mutual;
  for (const Association& a : pairs) {
    if (nearest_current[a.reference] == a.current) mutual.push_back(a);
  }
  return mutual;
}

struct NormalEquations {
  Eigen::Matrix3d H = Eigen::Matrix3d::Zero();
  Eigen::Vector3d b = Eigen::Vector3d::Zero();
  double chi2 = 0.0;
  int residuals = 0;  ///< scalar residuals: 2 per point-to-point pair, 1 per point-to-line pair
};

/// The reference side of the residuals: each point's sampling covariance and, where its
/// neighbours form a line, its unit normal (zero otherwise).
struct ReferenceGeometry {
  std::vector<Eigen::Matrix2d> sampling;
  std::vector<Eigen::Vector2d> normals;
};

/// One pair's residual e = q (+) p_j - a_i with its Jacobians and its weight Omega: W^-1 for a
/// point-to-point residual, n n^T / (n^T W n) for a point-to-line one (the scalar residual
/// n^T e of variance n^T W n), W = A_i + S_i + J_p C_j J_p^T.
struct PairResidual {
  Eigen::Vector2d e;
  Matrix23d J_q;
  Eigen::Matrix2d J_p;
  Eigen::Matrix2d Omega;
  bool line = false;
};

PairResidual pair_residual(const ScanPoint& reference, const ScanPoint& current,
                           const Eigen::Matrix2d& sampling, const Eigen::Vector2d& normal,
                           const Pose2& q) {
  PairResidual r;
  r.e = q.transform(current.p_m, &r.J_q, &r.J_p) - reference.p_m;
  const Eigen::Matrix2d W = reference.cov + sampling + r.J_p * current.cov * r.J_p.transpose();
  r.line = normal.squaredNorm() > 0.0;
  r.Omega = r.line ? Eigen::Matrix2d(normal * normal.transpose() / normal.dot(W * normal))
                   : Eigen::Matrix2d(W.inverse());
  return r;
}

/// M-step system at q: H = sum J_q^T Omega J_q, b = sum J_q^T Omega e.
NormalEquations normal_equations(const std::vector<ScanPoint>& reference,
                                 const ReferenceGeometry& geometry,
                                 const std::vector<ScanPoint>& current, const Pose2& q,
                                 const std::vector<Association>& pairs) {
  NormalEquations eq;
  for (const Association& a : pairs) {
    const PairResidual r =
        pair_residual(reference[a.reference], current[a.current], geometry.sampling[a.reference],
                      geometry.normals[a.reference], q);
    eq.H += r.J_q.transpose() * r.Omega * r.J_q;
    eq.b += r.J_q.transpose() * r.Omega * r.e;
    eq.chi2 += r.e.dot(r.Omega * r.e);
    eq.residuals += r.line ? 1 : 2;
  }
  return eq;
}

/// The estimate's covariance and its loading on the current scan's own errors.
struct ErrorPropagation {
  Eigen::Matrix3d cov;
  CurrentScanLoading current_loading;
  Eigen::Matrix3d current_share = Eigen::Matrix3d::Zero();    ///< H^-1 A_current H^-1
  Eigen::Matrix3d reference_share = Eigen::Matrix3d::Zero();  ///< H^-1 A_reference H^-1
  std::array<Eigen::Matrix3d, 2> reference_half{Eigen::Matrix3d::Zero(), Eigen::Matrix3d::Zero()};
};

/// The estimate as a function of every point's error (first order, at the solution):
/// dq = -H^-1 sum_j G_j de_j with G_j = J_q^T Omega_j, de_j = J_p dp_j - da_i + ds_j.
/// With `shared_point_errors`, cov(q) = H^-1 A H^-1 with A summing, over the joint covariance of
/// all de_j,
///   the current points' reading noise (own to each), the sampling error (own to each pair),
///   each reference point's reading noise times (sum of the G_j associated with it) on both sides,
///   and each half-scan's shared motion error (distortion * xi_side) summed over its points;
/// without, every residual is taken as independent and cov(q) = H^-1.
/// The loading on the current scan: -H^-1 G_j J_p on point j's noise (its reading noise, or its
/// whole covariance without shared errors) and -H^-1 sum G_j J_p D_j on its half's xi.
/// A point-to-line pair's Omega = n n^T / w keeps only the error along the normal.
ErrorPropagation propagate_point_errors(const std::vector<ScanPoint>& reference,
                                        const ReferenceGeometry& geometry,
                                        const std::vector<ScanPoint>& current, const Pose2& q,
                                        const std::vector<Association>& pairs,
                                        const Eigen::Matrix3d& H_inverse,
                                        bool shared_point_errors) {
  ErrorPropagation out;
  CurrentScanLoading& loading = out.current_loading;
  loading.whole_point_covariance = !shared_point_errors;
  loading.point.assign(current.size(), Eigen::Matrix<double, 3, 2>::Zero());
  // A = A_current + A_reference + A_sampling: the joint covariance of the de_j split by whose
  // error it is.
  Eigen::Matrix3d A_current = Eigen::Matrix3d::Zero();
  Eigen::Matrix3d A_reference = Eigen::Matrix3d::Zero();
  Eigen::Matrix3d A_sampling = Eigen::Matrix3d::Zero();
  std::vector<Eigen::Matrix<double, 3, 2>> U(reference.size(), Eigen::Matrix<double, 3, 2>::Zero());
  Eigen::Matrix3d B_current[2] = {Eigen::Matrix3d::Zero(), Eigen::Matrix3d::Zero()};
  Eigen::Matrix3d B_reference[2] = {Eigen::Matrix3d::Zero(), Eigen::Matrix3d::Zero()};
  for (const Association& a : pairs) {
    const ScanPoint& p = current[a.current];
    const ScanPoint& r = reference[a.reference];
    const Eigen::Matrix2d& S = geometry.sampling[a.reference];
    const PairResidual pr = pair_residual(r, p, S, geometry.normals[a.reference], q);
    const Eigen::Matrix<double, 3, 2> G = pr.J_q.transpose() * pr.Omega;
    loading.point[a.current] = -H_inverse * G * pr.J_p;
    if (!shared_point_errors) {
      // Independent residuals, W_j = A_i + J_p C_j J_p^T + S_j: H^-1 = H^-1 (sum G W G^T) H^-1.
      A_current += G * pr.J_p * p.cov * pr.J_p.transpose() * G.transpose();
      A_reference += G * r.cov * G.transpose();
      A_sampling += G * S * G.transpose();
      continue;
    }
    A_current += G * pr.J_p * p.cov_reading * pr.J_p.transpose() * G.transpose();
    A_sampling += G * S * G.transpose();
    U[a.reference] += G;
    B_current[p.side == 1] += G * pr.J_p * p.distortion;
    B_reference[r.side == 1] -= G * r.distortion;
  }
  if (shared_point_errors) {
    for (std::size_t i = 0; i < reference.size(); ++i) {
      A_reference += U[i] * reference[i].cov_reading * U[i].transpose();
    }
    for (int side = 0; side < 2; ++side) {
      A_current += B_current[side] * B_current[side].transpose();
      A_reference += B_reference[side] * B_reference[side].transpose();
      loading.half[side] = -H_inverse * B_current[side];
      out.reference_half[side] = -H_inverse * B_reference[side];
    }
  }
  const auto sandwich = [&](const Eigen::Matrix3d& A) -> Eigen::Matrix3d {
    const Eigen::Matrix3d C = H_inverse * A * H_inverse;
    return 0.5 * (C + C.transpose());
  };
  out.current_share = sandwich(A_current);
  out.reference_share = sandwich(A_reference);
  out.cov = shared_point_errors ? sandwich(A_current + A_reference + A_sampling) : H_inverse;
  return out;
}

/// The sampling error of point-to-point residuals: a surface sampled every d metres has the true
/// counterpart of a point anywhere within +-d/2 along it, a variance of d^2/12 along the direction
/// u to the nearest neighbour: (d^2 / 12) u u^T per reference point.
std::vector<Eigen::Matrix2d> sampling_covariances(const std::vector<ScanPoint>& reference) {
  std::vector<Eigen::Matrix2d> sampling(reference.size(), Eigen::Matrix2d::Zero());
  for (std::size_t i = 0; i < reference.size(); ++i) {
    double best = std::numeric_limits<double>::infinity();
    Eigen::Vector2d to_nearest = Eigen::Vector2d::Zero();
    for (std::size_t k = 0; k < reference.size(); ++k) {
      const Eigen::Vector2d d = reference[k].p_m - reference[i].p_m;
      if (k != i && d.squaredNorm() < best) best = d.squaredNorm(), to_nearest = d;
    }
    if (std::isfinite(best)) sampling[i] = to_nearest * to_nearest.transpose() / 12.0;
  }
  return sampling;
}

/// With scale_covariance_by_residual: the covariance, its shares and loadings times the
/// residual's variance factor chi^2 / (residuals - 3) when above 1.
void scale_by_residual(const ScanMatchConfig& config, const NormalEquations& eq,
                       ScanMatchResult& result) {
  const double dof = eq.residuals - 3.0;
  if (!config.scale_covariance_by_residual || dof <= 0.0 || eq.chi2 / dof <= 1.0) return;
  const double variance_factor = eq.chi2 / dof;
  result.estimate.cov *= variance_factor;
  result.current_share *= variance_factor;
  result.reference_share *= variance_factor;
  // The loadings carry the same scale: their products make covariances.
  const double scale = std::sqrt(variance_factor);
  for (auto& L : result.current_loading.point) L *= scale;
  for (auto& M : result.current_loading.half) M *= scale;
  for (auto& M : result.reference_half) M *= scale;
}

}  // namespace

ScanMatchResult match_scans(const std::vector<ScanPoint>& reference,
                            const std::vector<ScanPoint>& current, const GaussianPose2& guess,
                            const ScanMatchConfig& config) {
  ScanMatchResult result;
  // Point-to-point everywhere, and with the normals where the config asks for point-to-line.
  const ReferenceGeometry points{
      sampling_covariances(reference),
      std::vector<Eigen::Vector2d>(reference.size(), Eigen::Vector2d::Zero())};
  ReferenceGeometry lines = points;
  if (config.point_to_line_estimate || config.point_to_line_covariance) {
    lines.normals = line_normals(reference, config.line);
  }
  const ReferenceGeometry& for_estimate = config.point_to_line_estimate ? lines : points;
  const ReferenceGeometry& for_covariance = config.point_to_line_covariance ? lines : points;
  GaussianPose2 q = guess;
  std::vector<Association> pairs;
  NormalEquations eq;
  for (result.iterations = 1; result.iterations <= config.max_iterations; ++result.iterations) {
    pairs = associate(reference, current, q, config.association_gate_chi2,
                      config.reciprocal_association);
    if (static_cast<int>(pairs.size()) < config.min_inliers) return result;
    eq = normal_equations(reference, for_estimate, current, q.mean, pairs);
    const Eigen::Vector3d step = -eq.H.ldlt().solve(eq.b);
    if (!step.allFinite()) return result;
    q.mean = Pose2(q.mean.vector() + step);
    if (step.head<2>().norm() < config.tolerance_m && std::abs(step(2)) < config.tolerance_rad) {
      result.converged = true;
      break;
    }
  }
  // The final system at the final estimate and associations.
  pairs =
      associate(reference, current, q, config.association_gate_chi2, config.reciprocal_association);
  result.inliers = static_cast<int>(pairs.size());
  if (result.inliers < config.min_inliers) return result;
  eq = normal_equations(reference, for_covariance, current, q.mean, pairs);
  result.information = eq.H;
  result.chi2 = eq.chi2;
  if (std::abs(eq.H.determinant()) < 1e-12) return result;
  result.estimate.mean = q.mean;
  ErrorPropagation errors =
      propagate_point_errors(reference, for_covariance, current, q.mean, pairs, eq.H.inverse(),
                             config.shared_point_errors);
  result.estimate.cov = errors.cov;
  result.current_loading = std::move(errors.current_loading);
  result.current_share = errors.current_share;
  result.reference_share = errors.reference_share;
  result.reference_half = errors.reference_half;
  scale_by_residual(config, eq, result);
  result.valid = true;
  return result;
}

Eigen::Matrix3d shared_current_covariance(const ScanMatchResult& a, const ScanMatchResult& b,
                                          const std::vector<ScanPoint>& current) {
  Eigen::Matrix3d cov = Eigen::Matrix3d::Zero();
  const CurrentScanLoading& la = a.current_loading;
  const CurrentScanLoading& lb = b.current_loading;
  if (la.point.size() != current.size() || lb.point.size() != current.size()) return cov;
  // Each match takes a point's error as the model it was built with: when one of them holds the
  // points independent, the whole covariance is its noise, and no half-scan term is shared.
  const bool whole = la.whole_point_covariance || lb.whole_point_covariance;
  for (std::size_t j = 0; j < current.size(); ++j) {
    cov +=
        la.point[j] * (whole ? current[j].cov : current[j].cov_reading) * lb.point[j].transpose();
  }
  if (!whole) {
    for (int side = 0; side < 2; ++side) cov += la.half[side] * lb.half[side].transpose();
  }
  return cov;
}

}  // namespace msislab
