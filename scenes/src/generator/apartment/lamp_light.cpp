#include "phyir/scenes/lamp_light.h"

#include "phyir/core/closest_point.h"

#include <cmath>
#include <limits>

namespace phyir::scenes {

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
