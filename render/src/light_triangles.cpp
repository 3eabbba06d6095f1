#include "phyir/render/light_triangles.h"

#include "phyir/core/safe_math.h"

namespace phyir::render {

std::vector<LightTriangle> light_triangles(const scenes::Scene& scene) {
  std::vector<LightTriangle> out;
  EmitterTwins twins;
  for (size_t m = 0; m < scene.meshes.size(); ++m) {
    const scenes::Mesh& mesh = scene.meshes[m];
    if (mesh.material < 0 || size_t(mesh.material) >= scene.materials.size()) continue;
    const scenes::Material& material = scene.materials[size_t(mesh.material)];
    if (!material.is_emissive()) continue;
    const glm::vec3 emission = glm::max(material.emission(), glm::vec3(0.0f));
    // Alpha (MASK or BLEND) makes what a triangle sends vary over it and lets what lies
    // behind show through: such emitters are only ever sampled.
    const bool uniform = !material.emissive_texture.present() && material.alpha_mode == scenes::AlphaMode::Opaque &&
                         is_finite(emission);
    for (const glm::uvec3& t : mesh.triangles) {
      if (t.x >= mesh.positions.size() || t.y >= mesh.positions.size() || t.z >= mesh.positions.size()) continue;
      LightTriangle tri;
      tri.mesh = int(m);
      tri.vertices = t;
      for (int k = 0; k < 3; ++k) tri.p[k] = mesh.positions[t[k]];
      const glm::vec3 n = glm::cross(tri.p[1] - tri.p[0], tri.p[2] - tri.p[0]);
      if (!(glm::dot(n, n) > 0.0f) || !is_finite(n)) continue;
      tri.normal = glm::normalize(n);
      tri.emission = emission;
      tri.two_sided = material.double_sided;
      tri.uniform = uniform;
      const scenes::TriangleCorners corners(tri.p[0], tri.p[1], tri.p[2]);
      if (twins.kept(corners) >= 0) continue;
      twins.keep(corners, int(out.size()), tri.two_sided);
      out.push_back(tri);
    }
  }
  return out;
}

}  // namespace phyir::render
