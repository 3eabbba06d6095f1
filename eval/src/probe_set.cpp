#include "phyir/eval/probe_set.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "phyir/core/image_resample.h"
#include "phyir/eval/ssim.h"

namespace phyir::eval {

void compared_grid(const view::ProbeMosaic& pred, const view::ProbeMosaic& gt, int* grid_h, int* grid_w) {
  const view::ProbeLayout &p = pred.layout, &g = gt.layout;
  const bool pred_coarser = int64_t(p.grid_height) * p.grid_width < int64_t(g.grid_height) * g.grid_width;
  *grid_h = pred_coarser ? p.grid_height : g.grid_height;
  *grid_w = pred_coarser ? p.grid_width : g.grid_width;
}

ProbeScore probe_ssim(const view::ProbeMosaic& pred, const view::ProbeMosaic& gt) {
  ProbeScore score;
  compared_grid(pred, gt, &score.grid_h, &score.grid_w);
  const Size texels = coarser({gt.layout.res_width, gt.layout.res_height}, {pred.layout.res_width, pred.layout.res_height});
  score.h = texels.height;
  score.w = texels.width;
  double sum = 0.0;
  for (int i = 0; i < score.grid_h; ++i)
    for (int j = 0; j < score.grid_w; ++j) {
      int pi, pj, gi, gj;
      view::nearest_cell(i, j, score.grid_h, score.grid_w, pred.layout.grid_height, pred.layout.grid_width, &pi, &pj);
      view::nearest_cell(i, j, score.grid_h, score.grid_w, gt.layout.grid_height, gt.layout.grid_width, &gi, &gj);
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
