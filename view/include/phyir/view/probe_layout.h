#pragma once
// How a grid of light probes is laid out in probes.exr (docs/probes.md, docs/conventions.md):
// a grid of H x W probes, each an h x w equirectangular image in the toolkit's one mapping
// (core/equirect.h), world-aligned like the panorama. The mosaic is (H h) x (W w): probe (i, j)
// (row i, column j) is the block of rows [i h, (i+1) h) and columns [j w, (j+1) w), and belongs
// to the panorama direction through the centre of grid cell (i, j): u = (j + 0.5) / W,
// v = (i + 0.5) / H. probe_mask.exr is H x W.
//
// The defaults are the paper's labels (sec. 3.2, C.1): a 16x32 probe per pixel of a 128x256
// grid for a 256x512 panorama.
#include <string>

#include <glm/glm.hpp>

namespace phyir::view {

struct ProbeLayout {
  int grid_height = 128;  // H: probes per column of the grid
  int grid_width = 256;   // W
  int res_height = 16;    // h: texels per probe, rows
  int res_width = 32;     // w

  int probe_count() const { return grid_height * grid_width; }
  int texels_per_probe() const { return res_height * res_width; }
  int mosaic_width() const { return grid_width * res_width; }
  int mosaic_height() const { return grid_height * res_height; }
  // The mosaic pixel (column, row) of texel t (row-major in the probe) of probe p (row-major in the grid).
  glm::ivec2 mosaic_pixel(int p, int t) const {
    return {(p % grid_width) * res_width + t % res_width, (p / grid_width) * res_height + t / res_width};
  }
  bool operator==(const ProbeLayout& o) const {
    return grid_height == o.grid_height && grid_width == o.grid_width && res_height == o.res_height &&
           res_width == o.res_width;
  }
  // Throws phyir::SettingError naming "probe.grid" or "probe.res" when a size is out of range.
  void validate() const;
};

// The cell of a grid_height x grid_width grid that contains the centre of cell (i, j) of a
// ci x cj grid: how probes of two grids are matched (a probe is the light at one surface point;
// averaging neighbours would mix the light of different surfaces across an edge).
void nearest_cell(int i, int j, int ci, int cj, int grid_height, int grid_width, int* oi, int* oj);

// Parses "HxW" (e.g. "128x256") of the setting `setting`; phyir::SettingError naming it otherwise.
void parse_size(const std::string& text, const std::string& setting, int* height, int* width);

}  // namespace phyir::view
