#include "eval/noise_model_fit.hpp"

#include <algorithm>
#include <array>
#include <cassert>
#include <cmath>
#include <limits>
#include <utility>

#include "stats/sample_statistics.hpp"

namespace msislab {

namespace {

/// log of the 2-D isotropic normal density N(d; 0, s I) at |d|^2 = q.
double log_normal_2d(double q, double s) { return -std::log(2.0 * M_PI * s) - 0.5 * q / s; }

/// E|e_own|^2 given d = e_own - e_other, e_own ~ N(0, v I), e_other ~ N(0, u I):
/// e_own | d ~ N(d v / (v + u), v u / (v + u) I).
double expected_square(double q, double v, double u) {
  const double w = v / (v + u);
  return q * w * w + 2.0 * v * u / (v + u);
}

}  // namespace

ContaminatedNormal fit_contaminated_normal(const std::vector<Eigen::Vector2d>& differences) {
  assert(differences.size() >= 10);
  std::vector<double> q;
  q.reserve(differences.size());
  for (const Eigen::Vector2d& d : differences) q.push_back(d.squaredNorm());
  // Start: the core from the median of |d|^2 (2 a chi^2_2, median 2 ln 2), outliers 3x wider.
  double a = std::max(median(q) / (4.0 * std::log(2.0)), 1e-30);
  double b = 9.0 * a, eps = 0.05;
  double previous_ll = -std::numeric_limits<double>::infinity();
  ContaminatedNormal fit;
  for (fit.iterations = 1; fit.iterations <= 2000; ++fit.iterations) {
    // Components: both core, one of each (two ways), both outliers.
    const std::array<double, 3> log_w = {2.0 * std::log1p(-eps),
                                         std::log(2.0) + std::log(eps) + std::log1p(-eps),
                                         2.0 * std::log(eps)};
    const std::array<double, 3> s = {2.0 * a, a + b, 2.0 * b};
    double num_a = 0.0, den_a = 0.0, num_b = 0.0, den_b = 0.0, outliers = 0.0, ll = 0.0;
    for (const double qk : q) {
      std::array<double, 3> l;
      for (int c = 0; c < 3; ++c) l[c] = log_w[c] + log_normal_2d(qk, s[c]);
      const double l_max = *std::max_element(l.begin(), l.end());
      double sum = 0.0;
      for (double& lc : l) sum += (lc = std::exp(lc - l_max));
      ll += l_max + std::log(sum);
      const double r00 = l[0] / sum, r01 = l[1] / sum, r11 = l[2] / sum;
      outliers += r01 + 2.0 * r11;
      num_a += 2.0 * r00 * expected_square(qk, a, a) + r01 * expected_square(qk, a, b);
      den_a += 4.0 * r00 + 2.0 * r01;
      num_b += 2.0 * r11 * expected_square(qk, b, b) + r01 * expected_square(qk, b, a);
      den_b += 4.0 * r11 + 2.0 * r01;
    }
    eps = std::clamp(outliers / (2.0 * static_cast<double>(q.size())), 1e-9, 1.0 - 1e-9);
    a = num_a / den_a;
    if (den_b > 1e-12) b = num_b / den_b;
    if (ll - previous_ll < 1e-10 * std::abs(ll)) break;
    previous_ll = ll;
  }
  if (a > b) {  // the label with the larger variance is the outlier one
    std::swap(a, b);
    eps = 1.0 - eps;
  }
  fit.core_sigma = std::sqrt(a);
  fit.outlier_sigma = std::sqrt(b);
  fit.outlier_fraction = eps;
  return fit;
}

namespace {

/// The emission probabilities of sample k: p(s) = P(lost | s) when it was lost, else 1 - p(s).
Eigen::Vector2d emission(const std::vector<bool>& lost, const Eigen::Vector2d& p, std::size_t k) {
  return lost[k] ? p : Eigen::Vector2d(Eigen::Vector2d::Ones() - p);
}

/// Scaled forward-backward (Rabiner 1989, eqs. 91-93): fills alpha, beta and the scales, returns
/// the log-likelihood.
double forward_backward(const std::vector<bool>& lost, const Eigen::Matrix2d& A,
                        const Eigen::Vector2d& p, const Eigen::Vector2d& pi,
                        std::vector<Eigen::Vector2d>& alpha, std::vector<Eigen::Vector2d>& beta,
                        std::vector<double>& scale) {
  const std::size_t n = lost.size();
  alpha[0] = pi.cwiseProduct(emission(lost, p, 0));
  for (std::size_t k = 0; k < n; ++k) {
    if (k > 0) alpha[k] = (A.transpose() * alpha[k - 1]).cwiseProduct(emission(lost, p, k));
    scale[k] = alpha[k].sum();
    alpha[k] /= scale[k];
  }
  beta[n - 1] = Eigen::Vector2d::Ones();
  for (std::size_t k = n - 1; k > 0; --k) {
    beta[k - 1] = A * emission(lost, p, k).cwiseProduct(beta[k]) / scale[k];
  }
  double ll = 0.0;
  for (const double c : scale) ll += std::log(c);
  return ll;
}

}  // namespace

GilbertElliott fit_gilbert_elliott(const std::vector<bool>& lost) {
  const std::size_t n = lost.size();
  const double loss_fraction =
      static_cast<double>(std::count(lost.begin(), lost.end(), true)) / static_cast<double>(n);
  assert(loss_fraction > 0.0 && loss_fraction < 1.0);
  // State 0 clear, 1 degraded. A(i, j) = P(next j | now i); p(s) = P(lost | s).
  Eigen::Matrix2d A;
  A << 0.99, 0.01, 0.05, 0.95;
  Eigen::Vector2d p(0.25 * loss_fraction, std::min(0.5, 4.0 * loss_fraction));
  Eigen::Vector2d pi(A(1, 0), A(0, 1));
  pi /= pi.sum();
  std::vector<Eigen::Vector2d> alpha(n), beta(n);
  std::vector<double> scale(n);
  GilbertElliott fit;
  double previous_ll = -std::numeric_limits<double>::infinity();
  for (fit.iterations = 1; fit.iterations <= 5000; ++fit.iterations) {
    const double ll = forward_backward(lost, A, p, pi, alpha, beta, scale);
    // Re-estimation (eqs. 40a-c, 109-110).
    Eigen::Matrix2d xi_sum = Eigen::Matrix2d::Zero();
    Eigen::Vector2d gamma_sum = Eigen::Vector2d::Zero(), gamma_lost = Eigen::Vector2d::Zero();
    for (std::size_t k = 0; k < n; ++k) {
      const Eigen::Vector2d gamma = alpha[k].cwiseProduct(beta[k]);
      gamma_sum += gamma;
      if (lost[k]) gamma_lost += gamma;
      if (k + 1 < n) {
        const Eigen::Vector2d next =
            emission(lost, p, k + 1).cwiseProduct(beta[k + 1]) / scale[k + 1];
        xi_sum += (alpha[k] * next.transpose()).cwiseProduct(A);
      }
    }
    pi = alpha[0].cwiseProduct(beta[0]);
    for (int i = 0; i < 2; ++i) A.row(i) = xi_sum.row(i) / xi_sum.row(i).sum();
    p = gamma_lost.cwiseQuotient(gamma_sum);
    fit.log_likelihood = ll;
    if (ll - previous_ll < 1e-9) break;
    previous_ll = ll;
  }
  if (p(0) > p(1)) {  // the state that loses more is the degraded one
    std::swap(p(0), p(1));
    A = Eigen::Matrix2d(A.reverse());
  }
  fit.clear_loss_probability = p(0);
  fit.degraded_loss_probability = p(1);
  fit.degraded_fraction = A(0, 1) / (A(0, 1) + A(1, 0));
  fit.degraded_mean_samples = 1.0 / A(1, 0);
  return fit;
}

}  // namespace msislab
