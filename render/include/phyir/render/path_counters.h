#pragma once
// What the estimators count while they work: rays traced, paths started, non-finite
// samples caught. One mergeable struct, summed over threads after a parallel loop.
#include <cstdint>

namespace phyir::render {

struct PathCounters {
  uint64_t rays = 0;            // closest-hit and shadow rays
  uint64_t paths = 0;
  uint64_t nonfinite_samples = 0;  // NaN/Inf path contributions caught and zeroed

  PathCounters& operator+=(const PathCounters& o) {
    rays += o.rays;
    paths += o.paths;
    nonfinite_samples += o.nonfinite_samples;
    return *this;
  }
};

}  // namespace phyir::render
