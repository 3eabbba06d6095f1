#pragma once
// A grid of light probes as `probes.exr` + `probe_mask.exr` hold them (docs/probes.md):
// probe (i, j) is the h x w world-aligned equirect block at row i*h, column j*w of the mosaic,
// and belongs to the panorama direction u = (j + 0.5) / W, v = (i + 0.5) / H.
//
// Comparing two grids (docs/eval.md): probes are compared on the grid with fewer probes; the
// other side contributes, for each of its cells, the probe whose cell contains that cell's
// centre (nearest: a probe is the light at one surface point, averaging neighbours would mix
// the light of different surfaces across an edge). Texels are compared at the smaller texel
// resolution, the larger probe area-averaged onto it (equal solid-angle patches).
#include <filesystem>
#include <string>

#include "phyir/core/image.h"

namespace phyir::eval {

struct ProbeSet {
  int grid_h = 0, grid_w = 0;  // probes
  int h = 0, w = 0;            // texels per probe
  Image mosaic;                // (grid_h h) x (grid_w w), RGB linear radiance
  Image mask;                  // grid_w x grid_h, 1 = valid

  Image probe(int i, int j) const;  // h x w x 3
  bool valid(int i, int j) const { return mask.at(j, i, 0) > 0.5f; }
};

// Reads and checks the pair (mosaic divisible by the mask's grid, RGB, finite); errors name
// the files.
ProbeSet read_probe_set(const std::filesystem::path& mosaic, const std::filesystem::path& mask);

// A grid of `grid_h x grid_w` copies of one probe, every probe valid (the constant baseline).
ProbeSet constant_probe_set(const Image& probe, int grid_h, int grid_w);

// The cell of a grid_h x grid_w grid that contains the centre of cell (i, j) of a
// ci x cj grid.
void nearest_cell(int i, int j, int ci, int cj, int grid_h, int grid_w, int* oi, int* oj);

// Eq. 7 as a metric: mean over the compared probes (valid on both sides) of SSIM of
// log(1 + L) per probe (ssim.h's definition: CirP, 5x5 Gaussian, sigma 1.5).
struct ProbeScore {
  double ssim = 0.0;  // NaN when no probe is compared
  long probes = 0;
  int grid_h = 0, grid_w = 0, h = 0, w = 0;  // the compared grid and texel resolution
};
ProbeScore probe_ssim(const ProbeSet& pred, const ProbeSet& gt);

// The compared grid of two probe sets (the one with fewer probes; ties: the ground truth's).
void compared_grid(const ProbeSet& pred, const ProbeSet& gt, int* grid_h, int* grid_w);

}  // namespace phyir::eval
