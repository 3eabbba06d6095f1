#pragma once
// Inverse-variance weights of the probe loss's texels from the ground truth's standard error
// (TrainOptions::probe_loss_weight "stderr", docs/model.md "Probe loss weighting"). Private header.
#include <torch/torch.h>

namespace phyir::model {

// The label noise, in the loss's log1p space, at which a texel's weight halves.
inline constexpr double kProbeWeightTau = 0.1;

// w = 1 / (1 + (sigma / (tau (1 + Y)))^2) per texel, Y the ground truth's luminance and sigma
// its standard error (the same unit), then divided by its mean over the valid texels (probes
// in `mask`) so the weights average 1. gt_probes [B,H,W,h,w,3] linear, stderr [B,H,W,h,w,1],
// mask [B,1,H,W] (undefined: every probe). Returns [B,H,W,h,w,1], detached: weights are constants.
torch::Tensor probe_stderr_weights(const torch::Tensor& gt_probes, const torch::Tensor& stderr_probes,
                                   const torch::Tensor& mask, double tau = kProbeWeightTau);

}  // namespace phyir::model
