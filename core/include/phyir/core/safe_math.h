#pragma once
// The one place for numeric guards. Every epsilon here says why it has its value;
// code elsewhere calls these instead of sprinkling its own constants.
//
// NaN policy: these functions guard against *legal* inputs that are numerically bad
// (a cosine of 1 + 1 ulp, a zero-length vector, a pdf of 1e-30). A NaN argument is a bug
// upstream: it passes through (NaN in, NaN out) so that the path tracer's final
// is-finite check counts it (RenderStats: nonfinite_samples_caught) instead of hiding it.
//
// model/src/networks/safe_math.h mirrors the constants and functions for torch tensors; a test
// (tests/model/stability_test.cpp) keeps the two equal.
#include <glm/glm.hpp>

#include <algorithm>
#include <cmath>

namespace phyir {

constexpr float kPi = 3.14159265358979323846f;
constexpr float kTwoPi = 2.0f * kPi;
constexpr float kInvPi = 1.0f / kPi;
constexpr float kInvTwoPi = 1.0f / kTwoPi;

// Smallest cosine we divide by. Below this a direction is grazing to within
// 0.006 degrees; treating it as zero contribution avoids 1/cos fireflies.
constexpr float kMinCosine = 1e-4f;

// Denominators smaller than this are treated as zero (float has ~7 digits; a
// pdf of 1e-20 means the sample is impossible, not important).
constexpr float kTinyDenominator = 1e-20f;

// Squared lengths below this have no usable direction. A vector this short has
// components around 1e-15, whose squares (1e-30) are still normal floats (the smallest
// normal is 1.2e-38); much below it the squares go denormal or flush to zero and
// v / |v| loses its digits or becomes 0/0.
constexpr float kMinLength2 = 1e-30f;

// The largest float below 1 (1 - 2^-24): random numbers are remapped into [0, 1) with
// min(u, kOneMinusEpsilon) so that u * n never reaches n (an index one past the end).
constexpr float kOneMinusEpsilon = 0x1.fffffep-1f;

// Shadow rays towards a sampled point on a light stop this fraction short of it
// (tmax = distance * (1 - kShadowRayShortening)), a second guard against the light's own
// triangle being reported as the occluder (the first: both ends are offset off their
// surfaces, render/ray_offset.h shadow_ray_to; this margin alone is smaller than the
// origin's offset when a light is within ~0.6 m at room coordinates). 1e-4 of the
// distance is 0.1 mm at 1 m, well above float rounding of the hit distance (~6e-8
// relative) and far below any real gap.
constexpr float kShadowRayShortening = 1e-4f;

inline float safe_sqrt(float x) { return std::sqrt(std::max(x, 0.0f)); }
inline float safe_acos(float x) { return std::acos(std::clamp(x, -1.0f, 1.0f)); }
inline float safe_asin(float x) { return std::asin(std::clamp(x, -1.0f, 1.0f)); }
inline float clamp01(float x) { return std::clamp(x, 0.0f, 1.0f); }
// A cosine computed from rounded unit vectors can leave [-1, 1] by an ulp.
inline float clamp_cosine(float x) { return std::clamp(x, -1.0f, 1.0f); }

// a / b, or 0 when |b| is too small to mean anything.
inline float safe_div(float a, float b) {
  return std::abs(b) > kTinyDenominator ? a / b : 0.0f;
}
inline glm::vec3 safe_div(const glm::vec3& a, float b) {
  return std::abs(b) > kTinyDenominator ? a / b : glm::vec3(0.0f);
}

inline bool is_finite(float x) { return std::isfinite(x); }
inline bool is_finite(const glm::vec3& v) {
  return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z);
}

// x, or `fallback` when x is NaN or infinite (for values read from files and textures).
inline float finite_or(float x, float fallback) { return std::isfinite(x) ? x : fallback; }

// Normalises v, falling back to `fallback` for zero-length or non-finite input.
inline glm::vec3 safe_normalize(const glm::vec3& v, const glm::vec3& fallback) {
  const float len2 = glm::dot(v, v);
  if (!(len2 > kMinLength2) || !std::isfinite(len2)) return fallback;
  return v / std::sqrt(len2);
}

inline float luminance(const glm::vec3& c) {
  // Rec. 709 / sRGB primaries, the working space of the toolkit.
  return 0.2126f * c.x + 0.7152f * c.y + 0.0722f * c.z;
}

inline float max_component(const glm::vec3& c) { return std::max(c.x, std::max(c.y, c.z)); }

}  // namespace phyir
