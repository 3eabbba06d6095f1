#pragma once
// The mean of n Monte Carlo samples with its standard error, for tests that compare an
// estimator with an analytic value within a few standard errors.
#include <algorithm>
#include <cmath>

namespace phyir::test {

struct MeanAndError {
  double mean = 0.0, standard_error = 0.0;
};

// The mean of f(0), ..., f(n - 1).
template <typename F>
MeanAndError monte_carlo(int n, F&& f) {
  double sum = 0.0, sum2 = 0.0;
  for (int i = 0; i < n; ++i) {
    const double x = f(i);
    sum += x;
    sum2 += x * x;
  }
  MeanAndError r;
  r.mean = sum / n;
  r.standard_error = std::sqrt(std::max(0.0, sum2 / n - r.mean * r.mean) / n);
  return r;
}

}  // namespace phyir::test
