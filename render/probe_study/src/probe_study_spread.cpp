#include "phyir/render/probe_study_spread.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "phyir/core/error.h"

namespace phyir::render {

std::vector<double> per_probe_relative_rmse(const Image& a, const Image& b, const Image& reference, int probe_width,
                                            double factor) {
  if (a.width != b.width || a.height != b.height || a.width != reference.width || a.height != reference.height)
    fail("per-probe error: strips of {}x{}, {}x{} and {}x{} (reference) differ in size", a.width, a.height, b.width,
         b.height, reference.width, reference.height);
  if (probe_width <= 0 || a.width % probe_width != 0)
    fail("per-probe error: a strip {} texels wide is no whole number of probes {} wide", a.width, probe_width);
  const int probes = a.width / probe_width;
  std::vector<double> out(size_t(probes), 0.0);
  for (int k = 0; k < probes; ++k) {
    double squared = 0.0, magnitude = 0.0;
    for (int y = 0; y < a.height; ++y)
      for (int x = k * probe_width; x < (k + 1) * probe_width; ++x)
        for (int ch = 0; ch < 3; ++ch) {
          const double d = double(a.at(x, y, ch)) - double(b.at(x, y, ch));
          squared += d * d;
          magnitude += std::abs(double(reference.at(x, y, ch)));
        }
    const double n = 3.0 * double(a.height) * double(probe_width);
    out[size_t(k)] = magnitude > 0.0 ? factor * std::sqrt(squared / n) / (magnitude / n) : 0.0;
  }
  return out;
}

double quantile(std::vector<double> values, double q) {
  if (values.empty()) return std::numeric_limits<double>::quiet_NaN();
  std::sort(values.begin(), values.end());
  const double position = std::clamp(q, 0.0, 1.0) * double(values.size() - 1);
  const size_t below = size_t(std::floor(position));
  const size_t above = std::min(below + 1, values.size() - 1);
  const double t = position - double(below);
  return values[below] + t * (values[above] - values[below]);
}

ProbeSpread probe_spread(std::vector<double> per_probe) {
  ProbeSpread s;
  s.median = quantile(per_probe, 0.5);
  s.p90 = quantile(per_probe, 0.9);
  s.relative_rmse = std::move(per_probe);
  return s;
}

}  // namespace phyir::render
