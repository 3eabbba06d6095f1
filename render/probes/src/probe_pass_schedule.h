#pragma once
// The settings of each pass of a view's probes towards an error target (probe_error_target.h;
// docs/probes.md, "Accuracy as a target"): progressive, so that the mean of the passes is
// consistent.
//
// Cache mode reuses light across space through kernels of fixed width: the radiance cache's
// cells (interpolation, the 3x3x3 smoothing, one-sided at concave edges), the distance beyond
// which a cell caches direct light, and sharing's parallax bound. Each biases a pass by an
// amount that shrinks with its kernel, so pass k (k = 0 the first) takes every kernel
// shrunk by s_k = (k + 1)^(-1/3), as progressive photon mapping shrinks its radius between
// passes (Hachisuka and Jensen 2009; Knaus and Zwicker 2011): a bias of order s_k^2 averages
// over n passes to order n^(-2/3), which vanishes. Photon mapping must shrink slowly (its
// radius as n^(-1/6)) because fewer photons fall in a smaller disc; a cell keeps its number
// of fill estimates whatever its size, so a pass's noise stays about the same and the mean's
// still falls as n^(-1/2), faster than the bias: the price is the fill's cost, the cells
// growing in number as s_k^(-2).
//   - the cache's cell: cell_size x s_k;
//   - direct light cached from the same distance in metres (direct_distance_cells / s_k): the
//     interpolation's error at that distance, ~0.75 (cell / distance)^2, then shrinks as s_k^2;
//   - sharing's parallax bound: parallax_texels x s_k;
//   - where a specular chain ends on a glossy y (the chain's cap, or a polished y seen in a
//     rough lobe: path regularisation), the cache's uniformly lit lobe at y is replaced by the
//     path tracer's own light from y with probability 1 - s_k^2, so the approximation's bias,
//     (1 - p) times its error, shrinks as s_k^2 too. On a rough y (roughness >=
//     glossy_roughness) the lobe stays: nearly uniform, its error is a small part of a small
//     specular share, and a full path there would double a pass's cost.
// The photons are combined with the directions by multiple importance sampling and need no
// schedule.
#include "phyir/render/probe_settings.h"

namespace phyir::render {

// The shrink factor of pass k: (k + 1)^(-1/3).
float pass_shrink(int k);

// Pass k's settings: `base` with a seed of its own (k > 0) and, when base.progressive, its
// kernels shrunk by pass_shrink(k). Pass 0 is `base` itself.
ProbeSettings pass_settings(const ProbeSettings& base, int k);

}  // namespace phyir::render
