// Inverse-variance probe texel weights (probe_weights.h).
#include "probe_weights.h"

#include "batch_share.h"

namespace phyir::model {

torch::Tensor probe_stderr_weights(const torch::Tensor& gt_probes, const torch::Tensor& stderr_probes,
                                   const torch::Tensor& mask_in, double tau) {
  torch::NoGradGuard no_grad;
  const int64_t B = gt_probes.size(0), H = gt_probes.size(1), W = gt_probes.size(2);
  const torch::Tensor rec709 = torch::tensor({0.2126, 0.7152, 0.0722}, gt_probes.options());
  const torch::Tensor luminance = (gt_probes * rec709).sum(-1, true).abs();
  // The loss compares log1p(L): noise sigma in L is sigma / (1 + L) there (first order).
  const torch::Tensor log_sigma = stderr_probes.to(gt_probes.dtype()) / (1.0 + luminance);
  const torch::Tensor w = 1.0 / (1.0 + (log_sigma / tau).square());
  const torch::Tensor mask = mask_in.defined() ? mask_in.to(w.dtype()).reshape({B, H, W, 1, 1, 1})
                                               : torch::ones({B, H, W, 1, 1, 1}, w.options());
  const torch::Tensor valid = mask.expand_as(w);
  // Mean over the global batch's valid texels (every rank's, batch_share.h).
  const torch::Tensor mean = batch_sum((w * valid).sum()) / batch_sum(valid.sum()).clamp_min(1.0);
  return (w / mean.clamp_min(1e-12)).detach();
}

}  // namespace phyir::model
