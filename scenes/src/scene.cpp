#include "phyir/scenes/scene.h"

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

Bounds Scene::compute_bounds() const {
  Bounds b;
  for (const Mesh& m : meshes)
    for (const glm::vec3& p : m.positions) b.extend(p);
  return b;
}

}  // namespace phyir::scenes
