#pragma once
// Deterministic random numbers for rendering. Every pixel sample gets its own stream
// derived from (seed, pixel, sample), so images do not depend on thread count or tile order.
#include <cstdint>

#include "phyir/core/pcg32.h"

namespace phyir::render {

using Rng = Pcg32;
using phyir::mix64;

// The stream for one pixel sample of one render.
inline Rng pixel_sample_rng(uint64_t seed, uint64_t pixel_index, uint64_t sample_index) {
  return Rng(mix64(seed ^ mix64(pixel_index)), mix64(sample_index) ^ pixel_index);
}

}  // namespace phyir::render
