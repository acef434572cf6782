// A fixture for tests/layering_test.sh (never compiled): a command file that computes a statistic
// of its own, which the check must report (the ctest Architecture.LayeringCatchesStatisticsInApp).
#include <algorithm>
#include <vector>

double median_of(std::vector<double> values) {
  std::nth_element(values.begin(), values.begin() + values.size() / 2, values.end());
  return values[values.size() / 2];
}
