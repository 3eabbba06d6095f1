#include "phyir/view/probe_mosaic.h"

#include <cmath>

#include "phyir/core/error.h"
#include "phyir/core/image_io.h"
#include "phyir/core/image_resample.h"
#include "phyir/view/view_files.h"

namespace fs = std::filesystem;

namespace phyir::view {

Image probe_image(const Image& mosaic, const ProbeLayout& layout, int i, int j) {
  Image out(layout.res_width, layout.res_height, mosaic.channels);
  for (int r = 0; r < layout.res_height; ++r)
    for (int c = 0; c < layout.res_width; ++c)
      for (int ch = 0; ch < mosaic.channels; ++ch)
        out.at(c, r, ch) = mosaic.at(j * layout.res_width + c, i * layout.res_height + r, ch);
  return out;
}

Image ProbeMosaic::probe(int i, int j) const { return probe_image(radiance, layout, i, j); }

ProbeMosaic ProbeMosaic::scaled(double scale) const {
  ProbeMosaic out = *this;
  for (float& v : out.radiance.pixels) v = float(double(v) * scale);
  for (float& v : out.standard_error.pixels) v = float(double(v) * std::abs(scale));
  return out;
}

namespace {

void put_probe(ProbeMosaic& mosaic, int i, int j, const Image& probe) {
  const int h = mosaic.layout.res_height, w = mosaic.layout.res_width;
  for (int r = 0; r < h; ++r)
    for (int c = 0; c < w; ++c)
      for (int k = 0; k < 3; ++k) mosaic.radiance.at(j * w + c, i * h + r, k) = probe.at(c, r, k);
}

}  // namespace

ProbeMosaic ProbeMosaic::resampled(const ProbeLayout& target) const {
  if (target == layout) {
    ProbeMosaic same = *this;
    same.standard_error = Image();
    return same;
  }
  ProbeMosaic out;
  out.layout = target;
  out.radiance = Image(target.mosaic_width(), target.mosaic_height(), 3);
  out.mask = Image(target.grid_width, target.grid_height, 1);
  const Size texels{target.res_width, target.res_height};
  for (int i = 0; i < target.grid_height; ++i)
    for (int j = 0; j < target.grid_width; ++j) {
      int si, sj;
      nearest_cell(i, j, target.grid_height, target.grid_width, layout.grid_height, layout.grid_width, &si, &sj);
      put_probe(out, i, j, at_size(probe(si, sj), texels));
      out.mask.at(j, i, 0) = mask.at(sj, si, 0);
    }
  return out;
}

ProbeMosaic constant_probe_mosaic(const Image& probe, int grid_height, int grid_width) {
  ProbeMosaic s;
  s.layout = {grid_height, grid_width, probe.height, probe.width};
  s.radiance = Image(s.layout.mosaic_width(), s.layout.mosaic_height(), 3);
  for (int i = 0; i < grid_height; ++i)
    for (int j = 0; j < grid_width; ++j) put_probe(s, i, j, probe);
  s.mask = Image(grid_width, grid_height, 1, 1.0f);
  return s;
}

bool has_probes(const fs::path& dir) {
  const bool probes = fs::is_regular_file(dir / kProbesFile), mask = fs::is_regular_file(dir / kProbeMaskFile);
  if (probes != mask)
    fail("{}: has {} but not {}", dir.string(), probes ? kProbesFile : kProbeMaskFile,
         probes ? kProbeMaskFile : kProbesFile);
  return probes;
}

ProbeMosaic read_probe_mosaic(const fs::path& dir) {
  const fs::path mosaic_path = dir / kProbesFile, mask_path = dir / kProbeMaskFile;
  ProbeMosaic s;
  s.radiance = take_channels(read_image(mosaic_path), 3, mosaic_path.string());
  s.mask = read_image(mask_path);
  if (s.mask.height <= 0 || s.mask.width <= 0 || s.radiance.height % s.mask.height != 0 ||
      s.radiance.width % s.mask.width != 0)
    fail("{}: {}x{} mosaic is not a whole number of probes of the {}x{} grid that {} gives", mosaic_path.string(),
         s.radiance.width, s.radiance.height, s.mask.width, s.mask.height, mask_path.string());
  s.layout = {s.mask.height, s.mask.width, s.radiance.height / s.mask.height, s.radiance.width / s.mask.width};
  for (float v : s.radiance.pixels)
    if (!std::isfinite(v)) fail("{}: holds a non-finite value", mosaic_path.string());
  const fs::path stderr_path = dir / kProbeStderrFile;
  if (fs::is_regular_file(stderr_path)) {
    s.standard_error = take_channels(read_image(stderr_path), 1, stderr_path.string());
    if (s.standard_error.width != s.radiance.width || s.standard_error.height != s.radiance.height)
      fail("{}: {}x{} does not match {} ({}x{})", stderr_path.string(), s.standard_error.width,
           s.standard_error.height, mosaic_path.string(), s.radiance.width, s.radiance.height);
  }
  return s;
}

std::vector<std::string> write_probe_images(const fs::path& dir, const ProbeImages& images) {
  write_image(dir / kProbesFile, images.radiance);
  write_image(dir / kProbePositionFile, images.position, {"X", "Y", "Z"});
  write_image(dir / kProbeNormalFile, images.normal, {"X", "Y", "Z"});
  write_image(dir / kProbeMaskFile, images.mask);
  if (images.standard_error.empty()) return {kProbesFile, kProbePositionFile, kProbeNormalFile, kProbeMaskFile};
  write_image(dir / kProbeStderrFile, images.standard_error);
  return {kProbesFile, kProbePositionFile, kProbeNormalFile, kProbeMaskFile, kProbeStderrFile};
}

void write_probe_mosaic(const fs::path& dir, const ProbeMosaic& probes) {
  write_image(dir / kProbesFile, probes.radiance);
  write_image(dir / kProbeMaskFile, probes.mask);
}

}  // namespace phyir::view
