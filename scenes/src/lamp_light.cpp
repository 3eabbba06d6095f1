#include "phyir/scenes/lamp_light.h"

#include <cmath>
#include <limits>

namespace phyir::scenes {

glm::vec3 closest_point_on_triangle(const glm::vec3& p, const glm::vec3& a, const glm::vec3& b, const glm::vec3& c) {
  const glm::vec3 ab = b - a, ac = c - a, ap = p - a;
  const float d1 = glm::dot(ab, ap), d2 = glm::dot(ac, ap);
  if (d1 <= 0.0f && d2 <= 0.0f) return a;
  const glm::vec3 bp = p - b;
  const float d3 = glm::dot(ab, bp), d4 = glm::dot(ac, bp);
  if (d3 >= 0.0f && d4 <= d3) return b;
  const float vc = d1 * d4 - d3 * d2;
  if (vc <= 0.0f && d1 >= 0.0f && d3 <= 0.0f) return a + ab * (d1 / (d1 - d3));
  const glm::vec3 cp = p - c;
  const float d5 = glm::dot(ab, cp), d6 = glm::dot(ac, cp);
  if (d6 >= 0.0f && d5 <= d6) return c;
  const float vb = d5 * d2 - d1 * d6;
  if (vb <= 0.0f && d2 >= 0.0f && d6 <= 0.0f) return a + ac * (d2 / (d2 - d6));
  const float va = d3 * d6 - d5 * d4;
  if (va <= 0.0f && (d4 - d3) >= 0.0f && (d5 - d6) >= 0.0f) return b + (c - b) * ((d4 - d3) / ((d4 - d3) + (d5 - d6)));
  const float denominator = va + vb + vc;
  if (!(std::abs(denominator) > 0.0f)) return a;  // degenerate: any corner is as near as its edges
  return a + ab * (vb / denominator) + ac * (vc / denominator);
}

namespace {

// The nearest point of any triangle of `meshes` to p; false when there are none.
bool nearest_surface_point(const std::vector<const AssetMesh*>& meshes, const glm::vec3& p, glm::vec3* best) {
  float best2 = std::numeric_limits<float>::infinity();
  for (const AssetMesh* mesh : meshes)
    for (size_t t = 0; t + 2 < mesh->indices.size(); t += 3) {
      const glm::vec3 q = closest_point_on_triangle(p, mesh->positions[mesh->indices[t]],
                                                    mesh->positions[mesh->indices[t + 1]],
                                                    mesh->positions[mesh->indices[t + 2]]);
      const float d2 = glm::dot(q - p, q - p);
      if (d2 < best2) best2 = d2, *best = q;
    }
  return best2 < std::numeric_limits<float>::infinity();
}

}  // namespace

glm::vec3 clear_of_surfaces(const std::vector<const AssetMesh*>& meshes, glm::vec3 at, float radius) {
  // A step can bring the light nearer another surface (inside a narrow shade): a few more.
  constexpr int kMaxSteps = 4;
  for (int step = 0; step < kMaxSteps; ++step) {
    glm::vec3 nearest(0.0f);
    if (!nearest_surface_point(meshes, at, &nearest)) break;
    const glm::vec3 away = at - nearest;
    const float distance = glm::length(away);
    if (distance >= radius) break;
    // On the surface itself: down, the way a hanging bulb is.
    const glm::vec3 direction = distance > 1e-6f ? away / distance : glm::vec3(0.0f, -1.0f, 0.0f);
    at = nearest + direction * radius;
  }
  return at;
}

}  // namespace phyir::scenes
