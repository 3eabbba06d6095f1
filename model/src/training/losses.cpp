// PhyIR's losses (eqs. 2-4, 7, 8, 11).
#include "losses.h"

#include "batch_share.h"
#include "nets.h"
#include "render_layer.h"

namespace F = torch::nn::functional;

namespace phyir::model {

namespace {

torch::Tensor full_mask(const torch::Tensor& x, const torch::Tensor& mask) {
  if (mask.defined()) return mask.to(x.dtype());
  return torch::ones({x.size(0), 1, x.size(2), x.size(3)}, x.options());
}

}  // namespace

torch::Tensor masked_mean(const torch::Tensor& x, const torch::Tensor& mask_in) {
  const torch::Tensor mask = full_mask(x, mask_in);
  const torch::Tensor count = batch_sum(mask) * x.size(1);
  return batch_sum(x * mask) / count.clamp_min(1.0);
}

torch::Tensor l2_loss(const torch::Tensor& pred, const torch::Tensor& gt, const torch::Tensor& mask) {
  return masked_mean((pred - gt).square(), mask);
}

torch::Tensor metalness_loss(const torch::Tensor& pred, const torch::Tensor& gt, const torch::Tensor& mask_in) {
  const torch::Tensor mask = full_mask(pred, mask_in);
  const torch::Tensor metal = (gt > 0.5).to(pred.dtype()) * mask;
  const torch::Tensor n = batch_sum(metal);
  const torch::Tensor mean_pred_metal = batch_sum(pred * metal) / n.clamp_min(1.0);  // 0 if no metal
  return l2_loss(pred, gt, mask) * (2.0 - mean_pred_metal);
}

torch::Tensor berhu_loss(const torch::Tensor& pred, const torch::Tensor& gt, const torch::Tensor& mask_in) {
  const torch::Tensor mask = full_mask(pred, mask_in);
  const torch::Tensor x = (pred - gt).abs();
  const torch::Tensor c = (0.2 * batch_max(x * mask)).clamp_min(1e-6);
  const torch::Tensor quad = (x * x + c * c) / (2.0 * c);
  return masked_mean(torch::where(x <= c, x, quad), mask);
}

torch::Tensor normal_cosine_loss(const torch::Tensor& pred, const torch::Tensor& gt, const torch::Tensor& mask) {
  return masked_mean((1.0 - (pred * gt).sum(1, true)).abs(), mask);
}

torch::Tensor gradient_loss(const torch::Tensor& pred, const torch::Tensor& gt, const torch::Tensor& mask_in) {
  const torch::Tensor mask = full_mask(pred, mask_in);
  const int64_t H = pred.size(2), W = pred.size(3);
  auto dx = [&](const torch::Tensor& t) { return t.narrow(3, 1, W - 1) - t.narrow(3, 0, W - 1); };
  auto dy = [&](const torch::Tensor& t) { return t.narrow(2, 1, H - 1) - t.narrow(2, 0, H - 1); };
  const torch::Tensor mx = mask.narrow(3, 1, W - 1) * mask.narrow(3, 0, W - 1);
  const torch::Tensor my = mask.narrow(2, 1, H - 1) * mask.narrow(2, 0, H - 1);
  return masked_mean((dx(pred) - dx(gt)).abs(), mx) + masked_mean((dy(pred) - dy(gt)).abs(), my);
}

torch::Tensor ssim_map(const torch::Tensor& x, const torch::Tensor& y, const torch::Tensor& weights) {
  const int64_t C = x.size(1);
  const int radius = 2;
  const double sigma = 1.5;
  torch::Tensor g = torch::arange(-radius, radius + 1, x.options());
  g = torch::exp(-(g * g) / (2.0 * sigma * sigma));
  g = g / g.sum();
  const torch::Tensor kernel = (g.view({-1, 1}) * g.view({1, -1})).expand({C, 1, 2 * radius + 1, 2 * radius + 1});
  auto blur = [&](const torch::Tensor& t) {
    return F::conv2d(cirpad(t, radius, radius), kernel.contiguous(), F::Conv2dFuncOptions().groups(C));
  };
  // Weighted local statistics: each texel enters the window's means and moments with its
  // weight, so a texel of weight 0 is as if it were missing.
  const torch::Tensor wt = weights.defined() ? weights.expand_as(x) : torch::Tensor();
  const torch::Tensor wsum = wt.defined() ? blur(wt).clamp_min(1e-12) : torch::Tensor();
  auto mean = [&](const torch::Tensor& t) { return wt.defined() ? blur(wt * t) / wsum : blur(t); };
  const double C1 = 0.01 * 0.01, C2 = 0.03 * 0.03;
  const torch::Tensor mx = mean(x), my = mean(y);
  const torch::Tensor sxx = mean(x * x) - mx * mx, syy = mean(y * y) - my * my, sxy = mean(x * y) - mx * my;
  return ((2.0 * mx * my + C1) * (2.0 * sxy + C2)) / ((mx * mx + my * my + C1) * (sxx + syy + C2));
}

torch::Tensor probe_ssim_loss(const torch::Tensor& pred_log, const torch::Tensor& gt_log, const torch::Tensor& mask_in,
                              const torch::Tensor& texel_weights) {
  const int64_t B = pred_log.size(0), H = pred_log.size(1), W = pred_log.size(2), h = pred_log.size(3),
                w = pred_log.size(4);
  const torch::Tensor mask = mask_in.defined() ? mask_in.to(pred_log.dtype()).reshape({B, H, W, 1, 1, 1})
                                               : torch::ones({B, H, W, 1, 1, 1}, pred_log.options());
  auto images = [&](const torch::Tensor& p, int64_t c) {
    return (p * mask).permute({0, 1, 2, 5, 3, 4}).reshape({B * H * W, c, h, w});
  };
  torch::Tensor s;  // per probe
  if (texel_weights.defined()) {
    const torch::Tensor tw = images(texel_weights.to(pred_log.dtype()), 1);
    s = (ssim_map(images(pred_log, 3), images(gt_log, 3), tw) * tw).mean({1, 2, 3});
  } else {
    s = ssim_map(images(pred_log, 3), images(gt_log, 3)).mean({1, 2, 3});
  }
  const torch::Tensor m = mask.reshape({B * H * W});
  const torch::Tensor probes = batch_sum(m);
  const torch::Tensor mean_ssim = batch_sum(s * m) / probes.clamp_min(1.0);
  // No probe counts: nothing to learn (0, not 0.5 (1 - 0)).
  return torch::where(probes > 0, 0.5 * (1.0 - mean_ssim), torch::zeros_like(mean_ssim));
}

torch::Tensor spatial_coherence_loss(const torch::Tensor& probes, const torch::Tensor& depth,
                                     const torch::Tensor& mask_in, double alpha) {
  const int64_t B = probes.size(0), H = probes.size(1), W = probes.size(2);
  const torch::Tensor mask = mask_in.defined() ? mask_in.to(probes.dtype())
                                               : torch::ones({B, 1, H, W}, probes.options());
  const torch::Tensor dirs = pixel_directions(static_cast<int>(H), static_cast<int>(W), probes.options());
  torch::Tensor total = torch::zeros({}, probes.options()), count = torch::zeros({}, probes.options());
  auto pair = [&](const torch::Tensor& lp, const torch::Tensor& lq, const torch::Tensor& dp,
                  const torch::Tensor& dq, const torch::Tensor& dirp, const torch::Tensor& dirq,
                  const torch::Tensor& m) {
    const torch::Tensor warped = warp_probes(lq, dp, dq, dirp, dirq);
    const torch::Tensor diff = (warped - lp).abs().mean({3, 4, 5});  // [B,H',W']
    const torch::Tensor weight = torch::exp(alpha * (dq - dp).abs()).squeeze(1).detach();
    const torch::Tensor mm = m.squeeze(1);
    total = total + (diff * weight * mm).sum();
    count = count + mm.sum();
  };
  // Right neighbours (the panorama wraps around in u).
  pair(probes, probes.roll(-1, 2), depth, depth.roll(-1, 3), dirs, dirs.roll(-1, 1),
       mask * mask.roll(-1, 3));
  // Lower neighbours.
  if (H > 1) {
    pair(probes.narrow(1, 0, H - 1), probes.narrow(1, 1, H - 1), depth.narrow(2, 0, H - 1),
         depth.narrow(2, 1, H - 1), dirs.narrow(0, 0, H - 1), dirs.narrow(0, 1, H - 1),
         mask.narrow(2, 0, H - 1) * mask.narrow(2, 1, H - 1));
  }
  return batch_sum(total) / batch_sum(count).clamp_min(1.0);
}

}  // namespace phyir::model
