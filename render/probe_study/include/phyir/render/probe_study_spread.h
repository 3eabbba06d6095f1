#pragma once
// How the error of a probe study spreads over its probes (docs/commands/bench.md, "phyir bench
// probes"): the pooled relative RMSE weighs every texel alike, so one bad probe under a lamp
// and many good ones can share a pooled figure with uniformly mediocre probes. Each probe's own
// relative RMSE (its RMSE over its texels and RGB / its own mean |reference|), and their median
// and 90th percentile, tell the two apart: a user's view sees individual probes.
#include <vector>

#include "phyir/core/image.h"

namespace phyir::render {

// Per probe of strips (probes side by side, probe_study_breakdown.h's probe_strip), each
// `probe_width` texels wide: RMSE of `a - b` over the probe's texels and RGB, times `factor`,
// divided by the probe's mean |reference| over the same texels (0 when that mean is 0). The
// reference's own noise per probe is (half 0, half 1, mean of halves, factor 0.5).
std::vector<double> per_probe_relative_rmse(const Image& a, const Image& b, const Image& reference, int probe_width,
                                            double factor = 1.0);

// The q-quantile (q in [0, 1]) with linear interpolation between order statistics (numpy's
// default: position q (n - 1) in the sorted values); NaN for no values.
double quantile(std::vector<double> values, double q);

struct ProbeSpread {
  std::vector<double> relative_rmse;  // per probe, in subset order
  double median = 0.0;
  double p90 = 0.0;
};
ProbeSpread probe_spread(std::vector<double> per_probe);

}  // namespace phyir::render
