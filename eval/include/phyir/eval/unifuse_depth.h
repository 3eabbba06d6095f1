#pragma once
// UniFuse's depth metrics (Jiang et al., "UniFuse: Unidirectional Fusion for 360 Panorama
// Depth Estimation", RA-L 2021), written from the definitions in its repository
// (alibaba/UniFuse-Unidirectional-Fusion: metrics.py compute_depth_metrics and Evaluator,
// evaluate.py, datasets/threeD60.py val_mask). The paper's Table 7 takes UniFuse's, BiFuse's
// and OmniDepth's rows from UniFuse; docs/eval.md lists every rule and where it bites.
#include "phyir/core/image.h"
#include "phyir/eval/pixel_metrics.h"

namespace phyir::eval {

// UniFuse's depth range in metres: its datasets' max_depth_meters and its metrics' clamps.
// float32 values, because UniFuse clamps float32 tensors (0.1f is 0.10000000149).
constexpr float kUnifuseMinDepth = 0.1f;
constexpr float kUnifuseMaxDepth = 10.0f;

// UniFuse's val_mask: a ground truth in (0, 10] m that is not NaN.
bool unifuse_counts(float gt);

// One image as UniFuse's evaluate.py scores it (it calls the Evaluator once per image):
// over the pixels where unifuse_counts(gt), gt and pred raised to 0.1 m; gt lowered to 10 m
// where gt > 10 *and where pred > 10* (UniFuse's clamp writes gt, so a prediction beyond
// 10 m is never capped); with `median_align`, pred scaled by median(gt) / median(pred), each
// median the lower middle value as torch.median returns it. Then MAE, AbsRel, SqRel
// (mean (g - p)^2 / g), RMSE, RMSE log = sqrt(mean (log10 g - log10 p)^2) (log10, not ln),
// log10 = mean |log10(p / g)|, delta_n = fraction with max(g / p, p / g) < 1.25^n.
// Clamps and scaling in float32 as UniFuse's tensors; sums in double. pred and gt: one
// channel, one size. Nothing counted: every metric NaN (UniFuse's mean of nothing), pixels 0.
DepthMetrics unifuse_depth_metrics(const Image& pred, const Image& gt, bool median_align);

}  // namespace phyir::eval
