#pragma once
// The toolkit's one auto-exposure rule, for every LDR image made from an HDR one (the
// dataset's input.png, `phyir render`'s color.png): the exposure maps a high percentile of
// the linear RGB values to a target just below white, so a sunlit room and a lamp-lit one
// both land in the display's range without clipping more than the brightest few percent.
#include "phyir/core/image.h"

namespace phyir {

struct AutoExposure {
  float stops = 0.0f;             // log2(target / percentile_value), 0 for a black image
  float percentile_value = 0.0f;  // the percentile of all RGB values (first 3 channels)
};

// A black or nearly black image would otherwise ask for an absurd gain.
constexpr float kMaxAutoExposureStops = 32.0f;

// The `percentile` (in [0, 1]) of all RGB values (sorted, index floor(percentile * n),
// clamped to n - 1) and the stops that map it to `target`, clamped to +-32 stops; 0 stops
// when that value is not positive and finite.
AutoExposure auto_exposure(const Image& linear, double percentile = 0.95, double target = 0.9);

}  // namespace phyir
