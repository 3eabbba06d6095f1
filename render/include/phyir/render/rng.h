#pragma once
// The renderer's random number generator. Streams are derived only through streams.h, so
// images do not depend on thread count or tile order.
#include <cstdint>

#include "phyir/core/pcg32.h"

namespace phyir::render {

using Rng = Pcg32;
using phyir::mix64;

}  // namespace phyir::render
