#include "phyir/eval/probe_set.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "phyir/core/error.h"
#include "phyir/core/image_io.h"
#include "phyir/eval/resample.h"
#include "phyir/eval/ssim.h"

namespace phyir::eval {

Image ProbeSet::probe(int i, int j) const {
  Image out(w, h, 3);
  for (int r = 0; r < h; ++r)
    for (int c = 0; c < w; ++c)
      for (int k = 0; k < 3; ++k) out.at(c, r, k) = mosaic.at(j * w + c, i * h + r, k);
  return out;
}

ProbeSet read_probe_set(const std::filesystem::path& mosaic_path, const std::filesystem::path& mask_path) {
  ProbeSet s;
  s.mosaic = take_channels(read_image(mosaic_path), 3, mosaic_path.string());
  s.mask = read_image(mask_path);
  s.grid_h = s.mask.height;
  s.grid_w = s.mask.width;
  if (s.grid_h <= 0 || s.grid_w <= 0 || s.mosaic.height % s.grid_h != 0 || s.mosaic.width % s.grid_w != 0)
    fail("{}: {}x{} mosaic is not a whole number of probes of the {}x{} grid that {} gives", mosaic_path.string(),
         s.mosaic.width, s.mosaic.height, s.grid_w, s.grid_h, mask_path.string());
  s.h = s.mosaic.height / s.grid_h;
  s.w = s.mosaic.width / s.grid_w;
  for (float v : s.mosaic.pixels)
    if (!std::isfinite(v)) fail("{}: holds a non-finite value", mosaic_path.string());
  return s;
}

ProbeSet constant_probe_set(const Image& probe, int grid_h, int grid_w) {
  ProbeSet s;
  s.grid_h = grid_h;
  s.grid_w = grid_w;
  s.h = probe.height;
  s.w = probe.width;
  s.mosaic = Image(grid_w * s.w, grid_h * s.h, 3);
  for (int i = 0; i < grid_h; ++i)
    for (int j = 0; j < grid_w; ++j)
      for (int r = 0; r < s.h; ++r)
        for (int c = 0; c < s.w; ++c)
          for (int k = 0; k < 3; ++k) s.mosaic.at(j * s.w + c, i * s.h + r, k) = probe.at(c, r, k);
  s.mask = Image(grid_w, grid_h, 1, 1.0f);
  return s;
}

void nearest_cell(int i, int j, int ci, int cj, int grid_h, int grid_w, int* oi, int* oj) {
  const double v = (i + 0.5) / ci, u = (j + 0.5) / cj;
  *oi = std::min(grid_h - 1, static_cast<int>(std::floor(v * grid_h)));
  *oj = std::min(grid_w - 1, static_cast<int>(std::floor(u * grid_w)));
}

void compared_grid(const ProbeSet& pred, const ProbeSet& gt, int* grid_h, int* grid_w) {
  const bool pred_coarser = int64_t(pred.grid_h) * pred.grid_w < int64_t(gt.grid_h) * gt.grid_w;
  *grid_h = pred_coarser ? pred.grid_h : gt.grid_h;
  *grid_w = pred_coarser ? pred.grid_w : gt.grid_w;
}

ProbeScore probe_ssim(const ProbeSet& pred, const ProbeSet& gt) {
  ProbeScore score;
  compared_grid(pred, gt, &score.grid_h, &score.grid_w);
  const Size texels = coarser({gt.w, gt.h}, {pred.w, pred.h});
  score.h = texels.height;
  score.w = texels.width;
  double sum = 0.0;
  for (int i = 0; i < score.grid_h; ++i)
    for (int j = 0; j < score.grid_w; ++j) {
      int pi, pj, gi, gj;
      nearest_cell(i, j, score.grid_h, score.grid_w, pred.grid_h, pred.grid_w, &pi, &pj);
      nearest_cell(i, j, score.grid_h, score.grid_w, gt.grid_h, gt.grid_w, &gi, &gj);
      if (!pred.valid(pi, pj) || !gt.valid(gi, gj)) continue;
      Image a = at_size(pred.probe(pi, pj), texels), b = at_size(gt.probe(gi, gj), texels);
      for (float& v : a.pixels) v = std::log1p(std::max(v, 0.0f));
      for (float& v : b.pixels) v = std::log1p(std::max(v, 0.0f));
      sum += ssim(a, b);
      ++score.probes;
    }
  score.ssim = score.probes ? sum / score.probes : std::numeric_limits<double>::quiet_NaN();
  return score;
}

}  // namespace phyir::eval
