#include "phyir/render/ray_offset.h"

#include <cmath>
#include <cstdint>
#include <cstring>

#include "phyir/core/safe_math.h"

namespace phyir::render {

namespace {

// Waechter & Binder, Ray Tracing Gems ch. 6, listing 6-1. Near the origin the float
// spacing is tiny, so a fixed offset (float_scale) is used below kOrigin; elsewhere the
// point moves by int_scale * n ULPs, which scales with the magnitude of the coordinate.
constexpr float kOrigin = 1.0f / 32.0f;
constexpr float kFloatScale = 1.0f / 65536.0f;
constexpr float kIntScale = 256.0f;

float offset_component(float p, float n) {
  const int32_t of_i = static_cast<int32_t>(kIntScale * n);
  int32_t bits;
  std::memcpy(&bits, &p, sizeof bits);
  // Moving away from zero means adding to the magnitude bits: subtract for negative p.
  bits += (p < 0.0f) ? -of_i : of_i;
  float p_i;
  std::memcpy(&p_i, &bits, sizeof p_i);
  return std::abs(p) < kOrigin ? p + kFloatScale * n : p_i;
}

}  // namespace

glm::vec3 offset_ray_origin(const glm::vec3& p, const glm::vec3& n) {
  return glm::vec3(offset_component(p.x, n.x), offset_component(p.y, n.y), offset_component(p.z, n.z));
}

glm::vec3 spawn_origin(const glm::vec3& p, const glm::vec3& geometric_normal, const glm::vec3& direction) {
  return offset_ray_origin(p, glm::dot(direction, geometric_normal) >= 0.0f ? geometric_normal : -geometric_normal);
}

Ray shadow_ray_to(const glm::vec3& p, const glm::vec3& geometric_normal, const glm::vec3& target,
                  const glm::vec3& target_normal) {
  return shadow_ray_between(spawn_origin(p, geometric_normal, target - p), target, target_normal);
}

Ray shadow_ray_between(const glm::vec3& origin, const glm::vec3& target, const glm::vec3& target_normal) {
  Ray ray;
  ray.origin = origin;
  const glm::vec3 end = spawn_origin(target, target_normal, ray.origin - target);
  const glm::vec3 d = end - ray.origin;
  const float length = std::sqrt(glm::dot(d, d));
  if (!(length > 0.0f) || !std::isfinite(length)) {
    ray.tmax = 0.0f;  // the ends coincide: nothing between them
    return ray;
  }
  ray.direction = d / length;
  ray.tmax = length * (1.0f - kShadowRayShortening);
  return ray;
}

}  // namespace phyir::render
