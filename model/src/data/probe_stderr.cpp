// A probe mosaic's standard error resampled as load_view resamples the probes (data.h).
#include "data.h"

#include "nets.h"

namespace phyir::model {

namespace {

// The matrices of `resize` from in_h x in_w to h x w: it is separable, out = My . x . Mx^T,
// and each is read off by resizing impulses (rows of each matrix sum to 1 in both of its modes).
std::pair<torch::Tensor, torch::Tensor> resize_matrices(int64_t in_h, int64_t in_w, int h, int w) {
  const auto opts = torch::TensorOptions().dtype(torch::kDouble);
  const torch::Tensor ey = torch::eye(in_h, opts).view({in_h, 1, in_h, 1}).expand({in_h, 1, in_h, in_w});
  const torch::Tensor ex = torch::eye(in_w, opts).view({in_w, 1, 1, in_w}).expand({in_w, 1, in_h, in_w});
  const torch::Tensor my = resize(ey.contiguous(), h, w).select(1, 0).select(2, 0).t();  // [h, in_h]
  const torch::Tensor mx = resize(ex.contiguous(), h, w).select(1, 0).select(1, 0).t();  // [w, in_w]
  return {my, mx};
}

}  // namespace

torch::Tensor nearest_grid(const torch::Tensor& probes, int Hr, int Wr) {
  const int64_t grid_h = probes.size(0), grid_w = probes.size(1);
  if (grid_h == Hr && grid_w == Wr) return probes;
  // The probe of the grid cell containing each target pixel centre.
  const auto opts = probes.options().dtype(torch::kDouble);
  const torch::Tensor rows = ((torch::arange(Hr, opts) + 0.5) * grid_h / Hr).floor().to(torch::kLong);
  const torch::Tensor cols = ((torch::arange(Wr, opts) + 0.5) * grid_w / Wr).floor().to(torch::kLong);
  return probes.index_select(0, rows).index_select(1, cols);
}

torch::Tensor resample_probe_stderr(const torch::Tensor& mosaic, const view::ProbeLayout& layout, int Hr, int Wr,
                                    int h, int w) {
  const int hp = layout.res_height, wp = layout.res_width;
  // Variances, not sigmas, are what a linear resampling carries: out = sum_i w_i L_i of
  // independent texels has var = sum_i w_i^2 var_i, so an area mean of n texels has
  // sigma = sqrt(sum sigma_i^2) / n (averaging the sigmas would claim no noise reduction).
  const torch::Tensor var = mosaic.narrow(0, 0, 1).to(torch::kDouble).square().expand({3, -1, -1});
  torch::Tensor v = mosaic_to_probes(var.unsqueeze(0), hp, wp).squeeze(0).select(4, 0);  // [Hg,Wg,hp,wp]
  if (hp != h || wp != w) {
    const auto [my, mx] = resize_matrices(hp, wp, h, w);
    v = torch::matmul(torch::matmul(my.square(), v), mx.square().t());
  }
  return nearest_grid(v, Hr, Wr).sqrt().to(torch::kFloat).unsqueeze(4).contiguous();
}

}  // namespace phyir::model
