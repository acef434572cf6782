// Sample statistics (mean, root mean square, quantile, median, two-sample KS distance), each with
// one stated rule: the one definition every library reports them with.
#pragma once

#include <vector>

namespace msislab {

/// The arithmetic mean of a sample (summed in order). NaN for an empty sample.
double mean(const std::vector<double>& values);

/// The root mean square of a sample, sqrt(sum v^2 / n): its spread about zero. NaN for an empty
/// sample.
double rms(const std::vector<double>& values);

/// The p-quantile of a sample (p clamped to [0, 1]) by linear interpolation between order
/// statistics (Hyndman and Fan's type 7, R's and NumPy's default): with the sample sorted as
/// x_0 <= ... <= x_{n-1}, h = (n - 1) p and x_floor(h) + (h - floor(h)) (x_floor(h)+1 -
/// x_floor(h)). NaN for an empty sample.
double quantile(std::vector<double> values, double p);

/// The middle value of a sample, or the mean of the two middle ones when the size is even (the
/// 0.5-quantile above, computed as (a + b) / 2). NaN for an empty sample.
double median(std::vector<double> values);

/// Two-sample Kolmogorov-Smirnov distance sup_x |F_a(x) - F_b(x)| between the empirical
/// distribution functions: 0 for identical samples, 1 for disjoint ones. NaN when either is empty.
double ks_distance(std::vector<double> a, std::vector<double> b);

}  // namespace msislab
