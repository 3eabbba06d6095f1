#include "phyir/render/emitter_visibility.h"

#include <array>

#include "phyir/core/safe_math.h"
#include "phyir/render/frame.h"
#include "phyir/render/ray_offset.h"

namespace phyir::render {

namespace {

// Whether the hit's face turns its back to the ray, i.e. the ray travels inside a solid.
// Winding is the only orientation there is (double-sided faces have a back too).
bool hits_a_back_face(const scenes::Scene& scene, const Ray& ray, const Hit& hit) {
  if (hit.mesh < 0 || size_t(hit.mesh) >= scene.meshes.size()) return false;
  const scenes::Mesh& mesh = scene.meshes[size_t(hit.mesh)];
  if (hit.triangle < 0 || size_t(hit.triangle) >= mesh.triangles.size()) return false;
  const glm::uvec3 t = mesh.triangles[size_t(hit.triangle)];
  const glm::vec3 n = glm::cross(mesh.positions[t.y] - mesh.positions[t.x], mesh.positions[t.z] - mesh.positions[t.x]);
  return glm::dot(n, ray.direction) > 0.0f;
}

bool side_is_enclosed(const scenes::Scene& scene, const Accelerator& accelerator, const glm::vec3& p0,
                      const glm::vec3& p1, const glm::vec3& p2, const glm::vec3& n) {
  // Points spread over the triangle (barycentric), kept off its edges where a neighbouring
  // face would be hit at a grazing distance of zero.
  static constexpr std::array<glm::vec3, 7> kPoints = {
      glm::vec3(1 / 3.0f, 1 / 3.0f, 1 / 3.0f), glm::vec3(0.7f, 0.15f, 0.15f), glm::vec3(0.15f, 0.7f, 0.15f),
      glm::vec3(0.15f, 0.15f, 0.7f),           glm::vec3(0.45f, 0.45f, 0.1f), glm::vec3(0.1f, 0.45f, 0.45f),
      glm::vec3(0.45f, 0.1f, 0.45f)};
  const Frame frame(n);
  const float s = std::sin(glm::radians(60.0f)), c = std::cos(glm::radians(60.0f));
  const std::array<glm::vec3, 5> directions = {glm::vec3(0, 0, 1), glm::vec3(s, 0, c), glm::vec3(-s, 0, c),
                                               glm::vec3(0, s, c), glm::vec3(0, -s, c)};
  for (const glm::vec3& b : kPoints) {
    const glm::vec3 p = b.x * p0 + b.y * p1 + b.z * p2;
    for (const glm::vec3& local : directions) {
      const glm::vec3 d = frame.to_world(local);
      const Ray ray{spawn_origin(p, n, d), d};
      Hit hit;
      if (!accelerator.intersect(ray, &hit, Coverage::kBlendAbsent) || !hits_a_back_face(scene, ray, hit)) return false;
    }
  }
  return true;
}

}  // namespace

bool emits_only_into_solids(const scenes::Scene& scene, const Accelerator& accelerator, const glm::vec3& p0,
                            const glm::vec3& p1, const glm::vec3& p2, const glm::vec3& normal, bool two_sided) {
  if (!is_finite(normal) || !(glm::dot(normal, normal) > 0.5f)) return false;
  if (!side_is_enclosed(scene, accelerator, p0, p1, p2, normal)) return false;
  return !two_sided || side_is_enclosed(scene, accelerator, p0, p1, p2, -normal);
}

}  // namespace phyir::render
