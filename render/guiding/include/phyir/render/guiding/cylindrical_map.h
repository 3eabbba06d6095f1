#pragma once
// The sphere of directions on the unit square by the cylindrical map of Müller et al. 2017
// (section 4): u = (cos theta + 1) / 2 with theta from world +z, v = phi / 2 pi. It preserves
// area (dw = d cos theta d phi = 4 pi du dv), so a density over the square divided by 4 pi is
// the density over the sphere.
#include <algorithm>
#include <cmath>

#include <glm/glm.hpp>

#include "phyir/core/safe_math.h"

namespace phyir::render::guiding {

// Solid angle per unit area of the square.
constexpr float kSphereArea = 4.0f * kPi;

// The square point of a unit direction, in [0, 1)^2.
inline glm::vec2 direction_to_square(const glm::vec3& d) {
  const float u = 0.5f * (clamp_cosine(d.z) + 1.0f);
  float v = std::atan2(d.y, d.x) * kInvTwoPi;
  if (v < 0.0f) v += 1.0f;
  return glm::vec2(std::min(u, kOneMinusEpsilon), std::min(v, kOneMinusEpsilon));
}

// The unit direction of a square point.
inline glm::vec3 square_to_direction(const glm::vec2& p) {
  const float cos_theta = clamp_cosine(2.0f * p.x - 1.0f);
  const float sin_theta = safe_sqrt(1.0f - cos_theta * cos_theta);
  const float phi = kTwoPi * p.y;
  return glm::vec3(sin_theta * std::cos(phi), sin_theta * std::sin(phi), cos_theta);
}

}  // namespace phyir::render::guiding
