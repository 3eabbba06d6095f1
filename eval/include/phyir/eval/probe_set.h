#pragma once
// Scoring a grid of light probes (view/probe_mosaic.h) against another (docs/eval.md):
// probes are compared on the grid with fewer probes; the other side contributes, for each of its cells, the probe whose cell contains that cell's
// centre (nearest: a probe is the light at one surface point, averaging neighbours would mix
// the light of different surfaces across an edge). Texels are compared at the smaller texel
// resolution, the larger probe area-averaged onto it (equal solid-angle patches).
#include "phyir/view/probe_mosaic.h"

namespace phyir::eval {

// Eq. 7 as a metric: mean over the compared probes (valid on both sides) of SSIM of
// log(1 + L) per probe (ssim.h's definition: CirP, 5x5 Gaussian, sigma 1.5).
struct ProbeScore {
  double ssim = 0.0;  // NaN when no probe is compared
  long probes = 0;
  int grid_h = 0, grid_w = 0, h = 0, w = 0;  // the compared grid and texel resolution
};
ProbeScore probe_ssim(const view::ProbeMosaic& pred, const view::ProbeMosaic& gt);

// The compared grid of two probe grids (the one with fewer probes; ties: the ground truth's).
void compared_grid(const view::ProbeMosaic& pred, const view::ProbeMosaic& gt, int* grid_h, int* grid_w);

}  // namespace phyir::eval
