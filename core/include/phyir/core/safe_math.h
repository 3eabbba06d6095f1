#pragma once
// The one place for numeric guards. Every epsilon here says why it has its value;
// code elsewhere calls these instead of sprinkling its own constants.
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

inline float safe_sqrt(float x) { return std::sqrt(std::max(x, 0.0f)); }
inline float safe_acos(float x) { return std::acos(std::clamp(x, -1.0f, 1.0f)); }
inline float safe_asin(float x) { return std::asin(std::clamp(x, -1.0f, 1.0f)); }
inline float clamp01(float x) { return std::clamp(x, 0.0f, 1.0f); }

// a / b, or 0 when |b| is too small to mean anything.
inline float safe_div(float a, float b) {
  return std::abs(b) > kTinyDenominator ? a / b : 0.0f;
}

inline bool is_finite(float x) { return std::isfinite(x); }
inline bool is_finite(const glm::vec3& v) {
  return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z);
}

// Normalises v, falling back to `fallback` for zero-length or non-finite input.
inline glm::vec3 safe_normalize(const glm::vec3& v, const glm::vec3& fallback) {
  const float len2 = glm::dot(v, v);
  if (!(len2 > 1e-30f) || !std::isfinite(len2)) return fallback;
  return v / std::sqrt(len2);
}

inline float luminance(const glm::vec3& c) {
  // Rec. 709 / sRGB primaries, the working space of the toolkit.
  return 0.2126f * c.x + 0.7152f * c.y + 0.0722f * c.z;
}

inline float max_component(const glm::vec3& c) { return std::max(c.x, std::max(c.y, c.z)); }

}  // namespace phyir
