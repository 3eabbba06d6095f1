#pragma once
// The settings of each pass towards an error target (probe_error_target.h; docs/probes.md,
// "Accuracy as a target", step 4). Pass k (k = 0 the first) shrinks cache mode's reuse kernels
// by s_k = (k + 1)^(-1/3), as progressive photon mapping does (Hachisuka and Jensen 2009; Knaus
// and Zwicker 2011), so their bias averages away over the passes while a pass's noise does not grow:
//   - the cache's cell: cell_size x s_k;
//   - direct light cached from the same distance in metres: direct_distance_cells / s_k;
//   - sharing's parallax bound: parallax_texels x s_k;
//   - a specular chain ending on a glossy y: the path tracer's light from y instead of the
//     cache's uniformly lit lobe, with probability 1 - s_k^2. A rough y (roughness >=
//     glossy_roughness) keeps the lobe: nearly uniform, and a full path would double a pass's cost.
// The photons are combined with the directions by multiple importance sampling: no schedule.
#include "phyir/render/probe_settings.h"

namespace phyir::render {

// Pass k's settings: `base` with a seed of its own (k > 0) and, when base.progressive, its
// kernels shrunk by (k + 1)^(-1/3). Pass 0 is `base` itself.
ProbeSettings pass_settings(const ProbeSettings& base, int k);

}  // namespace phyir::render
