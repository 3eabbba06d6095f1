#pragma once
// A view's light probes as probes.exr + probe_mask.exr hold them (probe_layout.h): the one
// reader and writer, and the one resampling between layouts.
#include <filesystem>

#include "phyir/core/image.h"
#include "phyir/view/probe_layout.h"

namespace phyir::view {

// Probe (i, j) of a mosaic laid out as `layout`: its res_width x res_height block, every channel
// of the mosaic (radiance, or a standard error).
Image probe_image(const Image& mosaic, const ProbeLayout& layout, int i, int j);

struct ProbeMosaic {
  ProbeLayout layout;
  Image radiance;  // mosaic_width x mosaic_height, RGB linear radiance
  Image mask;      // grid_width x grid_height, 1 channel: 1 = a valid label
  // mosaic_width x mosaic_height, 1 channel: each texel's standard error in luminance, as the
  // renderer estimates it (probe_stderr.exr); empty where the folder has none.
  Image standard_error;

  Image probe(int i, int j) const;  // res_width x res_height x 3
  bool valid(int i, int j) const { return mask.at(j, i, 0) > 0.5f; }
  // Every texel times `scale` (radiance_units.h).
  ProbeMosaic scaled(double scale) const;
  // On another layout: each probe of `target`'s grid is the source probe whose cell contains
  // its cell's centre (nearest_cell), its texels area-averaged (or bilinearly magnified) to
  // target's resolution; the mask follows the same cells. The standard error is left out.
  ProbeMosaic resampled(const ProbeLayout& target) const;
};

// A grid of copies of one probe, every probe valid (the constant baseline).
ProbeMosaic constant_probe_mosaic(const Image& probe, int grid_height, int grid_width);

// True when `dir` holds probes.exr. A folder with only one of probes.exr and probe_mask.exr:
// phyir::Error naming the folder and the missing file.
bool has_probes(const std::filesystem::path& dir);

// Reads and checks dir/probes.exr and dir/probe_mask.exr (the mosaic a whole number of probes
// of the mask's grid, RGB, finite), and dir/probe_stderr.exr when there (the mosaic's size);
// errors name the files.
ProbeMosaic read_probe_mosaic(const std::filesystem::path& dir);

// The probe files of a rendered view.
struct ProbeImages {
  Image radiance, position, normal, mask, standard_error;
};
// Writes probes.exr, probe_position.exr, probe_normal.exr, probe_mask.exr and (when not
// empty) probe_stderr.exr into `dir` (each atomically); returns their names in that order.
std::vector<std::string> write_probe_images(const std::filesystem::path& dir, const ProbeImages& images);
// Writes probes.exr and probe_mask.exr (a prediction's probes).
void write_probe_mosaic(const std::filesystem::path& dir, const ProbeMosaic& probes);

}  // namespace phyir::view
