#pragma once
// Orthonormal shading frame: local z is the normal. BRDFs work in this frame, so
// cos(theta) = v.z everywhere.
#include <glm/glm.hpp>

#include <cmath>

namespace phyir::render {

struct Frame {
  glm::vec3 t{1, 0, 0}, b{0, 1, 0}, n{0, 0, 1};

  Frame() = default;
  // Duff et al. 2017, "Building an Orthonormal Basis, Revisited": branchless and
  // continuous except at n.z = -1, with no normalisation needed.
  explicit Frame(const glm::vec3& normal) : n(normal) {
    const float sign = std::copysign(1.0f, n.z);
    const float a = -1.0f / (sign + n.z);
    const float bb = n.x * n.y * a;
    t = glm::vec3(1.0f + sign * n.x * n.x * a, sign * bb, -sign * n.x);
    b = glm::vec3(bb, sign + n.y * n.y * a, -n.y);
  }
  Frame(const glm::vec3& tangent, const glm::vec3& bitangent, const glm::vec3& normal)
      : t(tangent), b(bitangent), n(normal) {}

  glm::vec3 to_local(const glm::vec3& v) const {
    return glm::vec3(glm::dot(v, t), glm::dot(v, b), glm::dot(v, n));
  }
  glm::vec3 to_world(const glm::vec3& v) const { return t * v.x + b * v.y + n * v.z; }
};

}  // namespace phyir::render
