#pragma once
// The emissive triangles of a scene as the probe renderer's light helpers see them
// (EmitterFootprints: which texels a light may cover; EmitterCoverage: how much of them).
// Triangles without area (or with non-finite vertices) are left out: nothing hits them; so
// are coincident twins of a double-sided light's triangles (scenes/triangle_corners.h).
#include <glm/glm.hpp>

#include <unordered_map>
#include <vector>

#include "phyir/scenes/scene.h"
#include "phyir/scenes/triangle_corners.h"

namespace phyir::render {

struct LightTriangle {
  int mesh = -1;
  glm::uvec3 vertices{0};   // indices into the mesh's positions
  glm::vec3 p[3];
  glm::vec3 normal{0.0f};   // unit, as wound (the emitting side unless two-sided)
  glm::vec3 emission{0.0f}; // the material's emission (emissive factor x strength), >= 0
  bool two_sided = false;
  bool uniform = true;      // `emission` everywhere on it: no emissive texture, no alpha cut-out

  // Whether `origin` sees its emitting side (edge-on: no).
  bool seen_from(const glm::vec3& origin) const {
    const float side = glm::dot(normal, origin - p[0]);
    return side > 0.0f || (two_sided && side < 0.0f);
  }
};

std::vector<LightTriangle> light_triangles(const scenes::Scene& scene);

// The rule both light lists (light_triangles, EmitterSampler) use for twin triangles: a
// coincident copy (either winding) of a double-sided emitter's triangle already kept adds
// no light and is left out. A one-sided triangle's twin lights the other side: both stay.
class EmitterTwins {
 public:
  // The index the first triangle at these corners was kept under, or -1 (not a twin).
  int kept(const scenes::TriangleCorners& corners) const {
    const auto it = kept_.find(corners);
    return it == kept_.end() ? -1 : it->second;
  }
  void keep(const scenes::TriangleCorners& corners, int index, bool double_sided) {
    if (double_sided) kept_.emplace(corners, index);
  }

 private:
  std::unordered_map<scenes::TriangleCorners, int, scenes::TriangleCornersHash> kept_;
};

}  // namespace phyir::render
