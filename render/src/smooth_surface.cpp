#include "phyir/render/smooth_surface.h"

#include <algorithm>
#include <cmath>

#include "phyir/core/safe_math.h"

namespace phyir::render {

glm::vec3 smooth_surface_point(const scenes::Mesh& mesh, const glm::uvec3& tri, const glm::vec3& bary,
                               const glm::vec3& p, const glm::vec3& side) {
  const size_t n = mesh.positions.size();
  if (mesh.normals.size() != n || tri.x >= n || tri.y >= n || tri.z >= n) return p;
  glm::vec3 lift(0.0f);
  float longest_edge2 = 0.0f;
  for (int k = 0; k < 3; ++k) {
    const glm::vec3& vertex = mesh.positions[tri[k]];
    glm::vec3 normal = safe_normalize(mesh.normals[tri[k]], glm::vec3(0.0f));
    if (glm::dot(normal, side) < 0.0f) normal = -normal;  // the vertex's normal on the shaded side
    // Below the vertex's tangent plane (convex there): up onto it; above it: no lift.
    const float height = glm::dot(p - vertex, normal);
    if (height < 0.0f) lift -= bary[k] * height * normal;
    const glm::vec3 edge = mesh.positions[tri[(k + 1) % 3]] - vertex;
    longest_edge2 = std::max(longest_edge2, glm::dot(edge, edge));
  }
  // Only towards the shaded side, and never further than the triangle is wide (broken
  // normals must not throw the origin across the room).
  if (!(glm::dot(lift, side) > 0.0f) || !is_finite(lift) || glm::dot(lift, lift) > longest_edge2) return p;
  return p + lift;
}

}  // namespace phyir::render
