#pragma once
// The torch mirror of core/include/phyir/core/safe_math.h: the same constants (their float
// values, so float tensors compare exactly as the renderer's floats do) and tensor versions
// of the guards, written so that both the value AND the gradient stay finite everywhere
// (the core versions only need finite values). tests/model/stability_test.cpp checks that
// the constants equal core's and that every function has finite gradients at its edges.
// Private header (torch types).
//
// The names live in an inline namespace, so phyir::model::kMinCosine is this one; it also
// lets a file that still defines its own copy in phyir::model compile while it switches to
// this header (it must qualify: phyir::model::safe_math::kMinCosine).
#include <torch/torch.h>

namespace phyir::model {
inline namespace safe_math {

// --- The constants of core/safe_math.h (see there for why each has its value) --------------
constexpr double kMinCosine = static_cast<double>(1e-4f);
constexpr double kTinyDenominator = static_cast<double>(1e-20f);
constexpr double kMinLength2 = static_cast<double>(1e-30f);
constexpr double kOneMinusEpsilon = static_cast<double>(0x1.fffffep-1f);

// --- Gradient guards (torch only) ------------------------------------------------------------
// acos'(x) = -1/sqrt(1 - x^2) is infinite at +-1: safe_acos clamps to +-(1 - this). 1e-6 is
// 0.08 degrees from the pole, where |acos'| = 707; in float32 1 - 1e-6 is still below 1 (the
// spacing there is 6e-8).
constexpr double kAcosGradientMargin = 1e-6;

// sqrt'(x) = 1/(2 sqrt(x)) is infinite at 0: safe_sqrt takes the root of max(x, this), so its
// gradient is at most 1/(2e-10) = 5e9 and exactly 0 below it; the value differs from
// sqrt(max(x, 0)) by at most 1e-10.
constexpr double kSqrtFloor = kTinyDenominator;

// sqrt(max(x, kSqrtFloor)): finite value and gradient for every finite x.
inline torch::Tensor safe_sqrt(const torch::Tensor& x) { return torch::sqrt(x.clamp_min(kSqrtFloor)); }

// acos(clamp(x, -1 + margin, 1 - margin)): finite value and gradient for every finite x.
inline torch::Tensor safe_acos(const torch::Tensor& x) {
  return torch::acos(x.clamp(-1.0 + kAcosGradientMargin, 1.0 - kAcosGradientMargin));
}

inline torch::Tensor clamp01(const torch::Tensor& x) { return x.clamp(0.0, 1.0); }

// a / b where |b| > kTinyDenominator, else 0. The denominator is replaced by 1 where it is
// too small BEFORE dividing: torch::where(ok, a / b, 0) alone would still send 0 * inf = NaN
// back through the unused branch.
inline torch::Tensor safe_div(const torch::Tensor& a, const torch::Tensor& b) {
  const torch::Tensor ok = b.abs() > kTinyDenominator;
  const torch::Tensor q = a / torch::where(ok, b, torch::ones_like(b));
  return torch::where(ok, q, torch::zeros_like(q));
}

// v / |v| along the last dimension, or `fallback` (broadcastable) where |v|^2 <= kMinLength2
// or is not finite; the same guarded-denominator form as safe_div.
inline torch::Tensor safe_normalize(const torch::Tensor& v, const torch::Tensor& fallback) {
  const torch::Tensor len2 = (v * v).sum(-1, /*keepdim=*/true);
  const torch::Tensor ok = (len2 > kMinLength2) & torch::isfinite(len2);
  const torch::Tensor n = v / torch::sqrt(torch::where(ok, len2, torch::ones_like(len2)));
  return torch::where(ok, n, fallback.to(n.dtype()).expand_as(n));
}

}  // namespace safe_math
}  // namespace phyir::model
