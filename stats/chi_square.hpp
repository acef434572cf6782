// The chi-square distribution, for gates and consistency (NEES) bounds: Boost.Math's, exact to
// its precision, in every library that needs it.
#pragma once

#include <utility>

namespace msislab {

/// P(X > x) for X chi-square with dof > 0 degrees of freedom (x >= 0).
double chi2_survival(double x, double dof);

/// The p-quantile of the chi-square distribution with dof > 0 degrees of freedom: 0 for p <= 0,
/// infinity for p >= 1.
double chi2_quantile(double p, double dof);

/// Two-sided (1 - alpha) bounds of the average of n independent chi-square variables with dof
/// degrees of freedom each, as used for NEES tests: n times the average is chi-square with n dof
/// degrees of freedom, so [chi2_quantile(alpha / 2, n dof) / n, chi2_quantile(1 - alpha / 2,
/// n dof) / n] (../shared/docs/field-notes.md: N = 50, 3 DOF: [2.36, 3.72]).
std::pair<double, double> average_chi2_bounds(int n, int dof, double alpha = 0.05);

}  // namespace msislab
