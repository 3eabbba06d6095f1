#include "phyir/scenes/scene.h"

#include <algorithm>
#include <cmath>

namespace phyir::scenes {

glm::vec2 TextureTransform::apply(glm::vec2 uv) const {
  const float c = std::cos(rotation), s = std::sin(rotation);
  const glm::vec2 scaled = uv * scale;
  // KHR_texture_transform's rotation matrix [c s; -s c] (column-major in the spec).
  return glm::vec2(c * scaled.x + s * scaled.y, -s * scaled.x + c * scaled.y) + offset;
}

size_t Scene::triangle_count() const {
  size_t n = 0;
  for (const Mesh& m : meshes) n += m.triangles.size();
  return n;
}

float PunctualLight::spot_falloff(float cos_angle) const {
  // KHR_lights_punctual's reference implementation, including its floor on the ramp's width
  // (a cone whose inner angle reaches the outer one gets a hard edge, not a division by 0).
  const float cos_outer = std::cos(outer_cone_angle);
  const float scale = 1.0f / std::max(0.001f, std::cos(inner_cone_angle) - cos_outer);
  const float t = std::clamp((cos_angle - cos_outer) * scale, 0.0f, 1.0f);
  return t * t;
}

const char* to_string(PunctualLight::Type type) {
  switch (type) {
    case PunctualLight::Type::Point: return "point";
    case PunctualLight::Type::Spot: return "spot";
    default: return "directional";
  }
}

Bounds Scene::compute_bounds() const {
  Bounds b;
  for (const Mesh& m : meshes)
    for (const glm::vec3& p : m.positions) b.extend(p);
  return b;
}

}  // namespace phyir::scenes
