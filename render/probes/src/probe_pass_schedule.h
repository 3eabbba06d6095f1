#pragma once
// The settings of each pass towards an error target (probe_error_target.h). Pass k shrinks
// cache mode's reuse kernels by s_k = (k + 1)^(-1/3), as progressive photon mapping does, so
// their bias averages away over the passes (docs/probes.md, "Accuracy as a target", step 4).
#include "phyir/render/probe_settings.h"

namespace phyir::render {

// Pass k's settings: `base` with a seed of its own (k > 0) and, when base.progressive, its
// kernels shrunk by (k + 1)^(-1/3). Pass 0 is `base` itself.
ProbeSettings pass_settings(const ProbeSettings& base, int k);

}  // namespace phyir::render
