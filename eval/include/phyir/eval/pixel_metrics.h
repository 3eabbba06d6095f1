#pragma once
// Per-pixel metrics of the paper (sections 4.1, 4.3, D.4) over a mask. Every function takes
// prediction and ground truth at the same size and a one-channel mask (> 0.5 = counted) and
// returns NaN when no pixel counts (reported as null / "-"). Sums are in double.
#include "phyir/core/image.h"

namespace phyir::eval {

// Mean over counted pixels and all channels of (p - g)^2 (Table 2: base colour, roughness,
// metalness, re-rendered image).
double masked_mse(const Image& pred, const Image& gt, const Image& mask);

// Mean absolute error over counted pixels and channels (relighting, Table 5).
double masked_mae(const Image& pred, const Image& gt, const Image& mask);

// Mean angle in degrees between the (normalised) predicted and ground-truth normals
// (Table 2). A zero-length vector on either side counts as 90 degrees.
double mean_angular_error_deg(const Image& pred, const Image& gt, const Image& mask);

// The standard depth metrics (Eigen et al. 2014) under the toolkit's rules (depth protocol
// `toolkit`, the default): over pixels with a counted mask and ground truth > 0, predictions
// clamped below at kMinDepth (log needs a positive value), no upper cap, no median scaling
// (metric depth), RMSE log in ln. UniFuse's rules differ: unifuse_depth.h.
struct DepthMetrics {
  double mae = 0, abs_rel = 0, sq_rel = 0, rmse = 0, rmse_log = 0, log10 = 0;
  double delta1 = 0, delta2 = 0, delta3 = 0;  // fraction with max(p/g, g/p) < 1.25^n
  long pixels = 0;
};
constexpr float kMinDepth = 1e-3f;  // 1 mm: below any depth a room panorama holds
DepthMetrics depth_metrics(const Image& pred, const Image& gt, const Image& mask);

// Number of counted pixels.
long count_mask(const Image& mask);

}  // namespace phyir::eval
