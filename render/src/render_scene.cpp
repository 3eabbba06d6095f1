#include "phyir/render/render_scene.h"

#include <spdlog/spdlog.h>

#include <cmath>

#include "phyir/core/safe_math.h"
#include "phyir/render/frame.h"
#include "phyir/render/material_eval.h"

namespace phyir::render {

namespace {

const scenes::Material& default_material() {
  static const scenes::Material material;
  return material;
}

template <typename T>
bool has_attribute(const std::vector<T>& attribute, const scenes::Mesh& mesh) {
  return !attribute.empty() && attribute.size() == mesh.positions.size();
}

// Normal maps need per-vertex tangents (glTF does not define a tangent frame otherwise);
// say once, at load, which meshes will render without theirs.
void warn_about_missing_tangents(const scenes::Scene& scene) {
  int count = 0;
  std::string first;
  for (const scenes::Mesh& mesh : scene.meshes) {
    if (mesh.material < 0 || static_cast<size_t>(mesh.material) >= scene.materials.size()) continue;
    if (!scene.materials[mesh.material].normal_texture.present() || has_attribute(mesh.tangents, mesh)) continue;
    if (count++ == 0) first = mesh.name;
  }
  if (count > 0)
    spdlog::warn("{}: {} mesh(es) (first: '{}') have a normal texture but no tangents; their normal maps are ignored",
                 scene.source.empty() ? std::string("<scene>") : scene.source, count, first);
}

}  // namespace

RenderScene::RenderScene(const scenes::Scene& scene, std::unique_ptr<EnvironmentLight> environment)
    : scene_(&scene), accelerator_(scene), emitters_(scene, &accelerator_), environment_(std::move(environment)) {
  warn_about_missing_tangents(scene);
}

SurfaceInteraction RenderScene::interact(const Ray& ray, const Hit& hit) const {
  SurfaceInteraction si;
  si.distance = hit.t;
  si.mesh = hit.mesh;
  si.triangle = hit.triangle;
  const glm::vec3 along_ray = ray.origin + hit.t * ray.direction;
  const glm::vec3 facing_ray = safe_normalize(-ray.direction, glm::vec3(0.0f, 1.0f, 0.0f));

  if (hit.mesh < 0 || static_cast<size_t>(hit.mesh) >= scene_->meshes.size() || hit.triangle < 0 ||
      static_cast<size_t>(hit.triangle) >= scene_->meshes[hit.mesh].triangles.size()) {
    // Not a hit of this scene: a finite, facing placeholder rather than a crash.
    si.position = is_finite(along_ray) ? along_ray : ray.origin;
    si.geometric_normal = si.shading_normal = facing_ray;
    si.tangent = Frame(facing_ray).t;
    return si;
  }

  const scenes::Mesh& mesh = scene_->meshes[hit.mesh];
  const glm::uvec3 tri = mesh.triangles[hit.triangle];
  const glm::vec3 bary = barycentrics(hit.barycentric);
  const glm::vec3& p0 = mesh.positions[tri.x];
  const glm::vec3& p1 = mesh.positions[tri.y];
  const glm::vec3& p2 = mesh.positions[tri.z];

  // Position from the vertices, not origin + t * dir (whose error grows with the distance
  // travelled). Written as p0 + b1 e1 + b2 e2 so a coordinate shared by all three vertices
  // (axis-aligned walls) is reproduced exactly.
  si.position = p0 + (p1 - p0) * bary.y + (p2 - p0) * bary.z;
  if (!is_finite(si.position)) si.position = is_finite(along_ray) ? along_ray : ray.origin;

  // Geometric normal as wound; degenerate triangles fall back to the interpolated
  // normal, then to facing the ray.
  glm::vec3 interpolated(0.0f);
  if (has_attribute(mesh.normals, mesh))
    interpolated = safe_normalize(mesh.normals[tri.x] * bary.x + mesh.normals[tri.y] * bary.y +
                                      mesh.normals[tri.z] * bary.z,
                                  glm::vec3(0.0f));
  const bool has_interpolated = interpolated != glm::vec3(0.0f);
  glm::vec3 ng = safe_normalize(glm::cross(p1 - p0, p2 - p0), glm::vec3(0.0f));
  if (ng == glm::vec3(0.0f)) ng = has_interpolated ? interpolated : facing_ray;
  si.front_face = glm::dot(ray.direction, ng) < 0.0f;

  // Shading normal: interpolated, on the wound side (authored normals that disagree with
  // the winding are flipped rather than trusted).
  glm::vec3 ns = has_interpolated ? interpolated : ng;
  if (glm::dot(ns, ng) < 0.0f) ns = -ns;

  // Tangent: the mesh's (glTF TANGENT, w = handedness) or any, orthogonal to ns.
  const bool has_tangents = has_attribute(mesh.tangents, mesh);
  glm::vec3 tangent(0.0f);
  float handedness = 1.0f;
  if (has_tangents) {
    const glm::vec4 t = mesh.tangents[tri.x] * bary.x + mesh.tangents[tri.y] * bary.y + mesh.tangents[tri.z] * bary.z;
    tangent = glm::vec3(t);
    handedness = t.w < 0.0f ? -1.0f : 1.0f;
  }
  auto orthogonal_tangent = [](const glm::vec3& t, const glm::vec3& n) {
    return safe_normalize(t - n * glm::dot(n, t), Frame(n).t);
  };
  tangent = orthogonal_tangent(tangent, ns);

  si.material = mesh.material;
  const bool material_valid = mesh.material >= 0 && static_cast<size_t>(mesh.material) < scene_->materials.size();
  const scenes::Material& material = material_valid ? scene_->materials[mesh.material] : default_material();
  const MaterialPoint mp = evaluate_material(*scene_, mesh, material, tri, bary);

  // Normal map (glTF: n = T x + B y + N z, B = cross(N, T) * w). A perturbed normal that
  // would dip below the geometric surface is discarded, not bent.
  if (mp.has_normal_map && has_tangents) {
    const glm::vec3 bitangent = glm::cross(ns, tangent) * handedness;
    const glm::vec3 mapped =
        safe_normalize(tangent * mp.normal_ts.x + bitangent * mp.normal_ts.y + ns * mp.normal_ts.z, ns);
    if (glm::dot(mapped, ng) > 0.0f) {
      ns = mapped;
      tangent = orthogonal_tangent(tangent, ns);
    }
  }

  // Both normals point to the side the ray arrived from.
  if (!si.front_face) {
    ng = -ng;
    ns = -ns;
  }
  si.geometric_normal = ng;
  si.shading_normal = ns;
  si.tangent = tangent;

  if (has_attribute(mesh.texcoords0, mesh)) {
    const glm::vec2 uv = mesh.texcoords0[tri.x] * bary.x + mesh.texcoords0[tri.y] * bary.y +
                         mesh.texcoords0[tri.z] * bary.z;
    if (std::isfinite(uv.x) && std::isfinite(uv.y)) si.uv = uv;
  }

  si.brdf = mp.brdf;
  si.emits = (si.front_face || material.double_sided) && max_component(mp.emission) > 0.0f;
  si.emission = si.emits ? mp.emission : glm::vec3(0.0f);
  si.transmission = mp.transmission;
  si.ior = mp.ior;
  si.opacity = mp.opacity;
  return si;
}

bool RenderScene::trace(const Ray& ray, SurfaceInteraction* si) const {
  Hit hit;
  if (!accelerator_.intersect(ray, &hit)) return false;
  *si = interact(ray, hit);
  return true;
}

bool RenderScene::trace_emission(const Ray& ray, glm::vec3* emission, float* distance) const {
  Hit hit;
  if (!accelerator_.intersect(ray, &hit)) return false;
  *distance = hit.t;
  *emission = glm::vec3(0.0f);
  const bool known = hit.mesh >= 0 && static_cast<size_t>(hit.mesh) < scene_->meshes.size();
  const int material = known ? scene_->meshes[size_t(hit.mesh)].material : -1;
  const bool can_emit = !known || material < 0 || static_cast<size_t>(material) >= scene_->materials.size() ||
                        scene_->materials[size_t(material)].is_emissive();
  if (can_emit) *emission = interact(ray, hit).emission;
  return true;
}

}  // namespace phyir::render
