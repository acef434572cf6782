#include "stats/chi_square.hpp"

#include <boost/math/distributions/chi_squared.hpp>
#include <limits>

namespace msislab {

double chi2_survival(double x, double dof) {
  return boost::math::cdf(boost::math::complement(boost::math::chi_squared(dof), x));
}

double chi2_quantile(double p, double dof) {
  // The ends, which Boost reports as errors: a gate at probability 1 (the survival of an
  // infinite or huge gate underflows to 0) keeps everything.
  if (p >= 1.0) return std::numeric_limits<double>::infinity();
  if (p <= 0.0) return 0.0;
  return boost::math::quantile(boost::math::chi_squared(dof), p);
}

std::pair<double, double> average_chi2_bounds(int n, int dof, double alpha) {
  const double k = static_cast<double>(n) * dof;
  return {chi2_quantile(alpha / 2.0, k) / n, chi2_quantile(1.0 - alpha / 2.0, k) / n};
}

}  // namespace msislab
