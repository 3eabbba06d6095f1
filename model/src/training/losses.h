#pragma once
// The losses of PhyIR (sec. 3.2, eqs. 2-4, 7, 8, 11). Maps are [B,C,H,W]; masks are [B,1,H,W]
// with 1 where a pixel counts (an undefined tensor means "every pixel"). Every loss is a mean
// over the counted elements and returns 0 (not NaN) when nothing counts.
// Private header (torch types).
#include <torch/torch.h>

namespace phyir::model {

// Mean of x over the elements where mask (broadcast over channels) is 1.
torch::Tensor masked_mean(const torch::Tensor& x, const torch::Tensor& mask);

// L2 (mean squared error) for base colour and roughness; eq. 11 (re-render) is the same.
torch::Tensor l2_loss(const torch::Tensor& pred, const torch::Tensor& gt, const torch::Tensor& mask);

// Eq. 2: L2 x (2 - mean predicted metalness over the pixels that are metal in the ground
// truth, M > 0.5). With no metal pixel the factor is 2.
torch::Tensor metalness_loss(const torch::Tensor& pred, const torch::Tensor& gt, const torch::Tensor& mask);

// BerHu (reverse Huber, Laina et al. 2016): |x| for |x| <= c, (x^2 + c^2) / (2c) beyond,
// c = 0.2 max |x| over the batch (treated as a constant).
torch::Tensor berhu_loss(const torch::Tensor& pred, const torch::Tensor& gt, const torch::Tensor& mask);

// Eq. 3: mean |1 - n . n~|.
torch::Tensor normal_cosine_loss(const torch::Tensor& pred, const torch::Tensor& gt, const torch::Tensor& mask);

// Eq. 4: mean |d/dx X - d/dx X~| + mean |d/dy X - d/dy X~| (forward differences; a difference
// counts when both of its pixels are in the mask).
torch::Tensor gradient_loss(const torch::Tensor& pred, const torch::Tensor& gt, const torch::Tensor& mask);

// SSIM of two batches of images [N,C,h,w] with a 5x5 Gaussian window (sigma 1.5) and
// CirP borders (the images are equirect probes), C1 = 0.01^2, C2 = 0.03^2. Returns the SSIM
// map [N,C,h,w]. With `weights` ([N,1,h,w] or [N,C,h,w]) the window's means and moments are
// weighted by them (a texel of weight 0 does not enter its neighbours' statistics).
torch::Tensor ssim_map(const torch::Tensor& x, const torch::Tensor& y, const torch::Tensor& weights = {});

// Eq. 7: 0.5 (1 - SSIM(L_log . M, L~_log . M)) on per-pixel probes [B,H,W,h,w,3] (log space),
// the SSIM averaged over the probes of the pixels in the mask. With `texel_weights`
// [B,H,W,h,w,1] (probe_weights.h: mean 1 over the valid texels) each texel's SSIM term, and its
// share of its neighbours' window statistics, is weighted: equal weights give the unweighted loss.
torch::Tensor probe_ssim_loss(const torch::Tensor& pred_log, const torch::Tensor& gt_log,
                              const torch::Tensor& mask, const torch::Tensor& texel_weights = {});

// Eq. 8: mean over neighbouring pixel pairs (p, q) (right neighbour with wrap-around, lower
// neighbour) of |Warp_{q->p}(L~) - L~_p| e^{alpha |D~_q - D~_p|}, probes in log space
// [B,H,W,h,w,3], depth [B,1,H,W] at the probes' pixel grid. The weight is held constant
// (detached): differentiating it would reward depth discontinuities.
torch::Tensor spatial_coherence_loss(const torch::Tensor& probes_log, const torch::Tensor& depth,
                                     const torch::Tensor& mask, double alpha = -5.0);

}  // namespace phyir::model
