#include "phyir/render/render_scene.h"

#include <spdlog/spdlog.h>

#include <cmath>

#include "phyir/core/safe_math.h"
#include "phyir/render/frame.h"
#include "phyir/render/material_eval.h"
#include "phyir/render/smooth_surface.h"

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
  if (environment_) portals_ = EnvironmentPortals(scene.portals);
  warn_about_missing_tangents(scene);
}

namespace {

glm::vec3 orthogonal_tangent(const glm::vec3& t, const glm::vec3& n) {
  return safe_normalize(t - n * glm::dot(n, t), Frame(n).t);
}

// The frame of a hit from its triangle's vertices, on the wound side (flipped to the ray's
// side by the caller).
struct HitFrame {
  glm::vec3 ng{0.0f}, ns{0.0f}, tangent{0.0f};
  float handedness = 1.0f;
  bool has_tangents = false;
  bool front_face = true;
};

// A ray's pixel footprint on the surface it hits: (width + spread x distance)^2, stretched
// by 1 / |cos| of the incidence (capped at 100x at grazing angles).
TextureFootprint footprint(const Ray& ray, float distance, const glm::vec3& geometric_normal) {
  const float width = ray.width + ray.spread * distance;
  if (!(width > 0.0f)) return {};
  const float cos_incidence = std::max(std::abs(glm::dot(geometric_normal, ray.direction)), 0.01f);
  const float area = width * width / cos_incidence;
  return TextureFootprint{std::isfinite(area) ? area : 0.0f};
}

HitFrame hit_frame(const scenes::Mesh& mesh, const glm::uvec3& tri, const glm::vec3& bary, const Ray& ray,
                   const glm::vec3& facing_ray) {
  const glm::vec3& p0 = mesh.positions[tri.x];
  const glm::vec3& p1 = mesh.positions[tri.y];
  const glm::vec3& p2 = mesh.positions[tri.z];
  HitFrame f;
  // Geometric normal as wound; degenerate triangles fall back to the interpolated
  // normal, then to facing the ray.
  glm::vec3 interpolated(0.0f);
  if (has_attribute(mesh.normals, mesh))
    interpolated = safe_normalize(mesh.normals[tri.x] * bary.x + mesh.normals[tri.y] * bary.y +
                                      mesh.normals[tri.z] * bary.z,
                                  glm::vec3(0.0f));
  const bool has_interpolated = interpolated != glm::vec3(0.0f);
  f.ng = safe_normalize(glm::cross(p1 - p0, p2 - p0), glm::vec3(0.0f));
  if (f.ng == glm::vec3(0.0f)) f.ng = has_interpolated ? interpolated : facing_ray;
  f.front_face = glm::dot(ray.direction, f.ng) < 0.0f;
  // Shading normal: interpolated, on the wound side (authored normals that disagree with
  // the winding are flipped rather than trusted).
  f.ns = has_interpolated ? interpolated : f.ng;
  if (glm::dot(f.ns, f.ng) < 0.0f) f.ns = -f.ns;
  // Tangent: the mesh's (glTF TANGENT, w = handedness) or any, orthogonal to ns.
  f.has_tangents = has_attribute(mesh.tangents, mesh);
  if (f.has_tangents) {
    const glm::vec4 t = mesh.tangents[tri.x] * bary.x + mesh.tangents[tri.y] * bary.y + mesh.tangents[tri.z] * bary.z;
    f.tangent = glm::vec3(t);
    f.handedness = t.w < 0.0f ? -1.0f : 1.0f;
  }
  f.tangent = orthogonal_tangent(f.tangent, f.ns);
  return f;
}

// Normal map (glTF: n = T x + B y + N z, B = cross(N, T) * w). A perturbed normal that would
// dip below the geometric surface is discarded, not bent.
void apply_normal_map(const MaterialPoint& mp, HitFrame* f) {
  if (!mp.has_normal_map || !f->has_tangents) return;
  const glm::vec3 bitangent = glm::cross(f->ns, f->tangent) * f->handedness;
  const glm::vec3 mapped =
      safe_normalize(f->tangent * mp.normal_ts.x + bitangent * mp.normal_ts.y + f->ns * mp.normal_ts.z, f->ns);
  if (glm::dot(mapped, f->ng) > 0.0f) {
    f->ns = mapped;
    f->tangent = orthogonal_tangent(f->tangent, f->ns);
  }
}

}  // namespace

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
  // Position from the vertices, not origin + t * dir (whose error grows with the distance
  // travelled). Written as p0 + b1 e1 + b2 e2 so a coordinate shared by all three vertices
  // (axis-aligned walls) is reproduced exactly.
  si.position = p0 + (mesh.positions[tri.y] - p0) * bary.y + (mesh.positions[tri.z] - p0) * bary.z;
  if (!is_finite(si.position)) si.position = is_finite(along_ray) ? along_ray : ray.origin;

  HitFrame f = hit_frame(mesh, tri, bary, ray, facing_ray);
  si.front_face = f.front_face;
  si.material = mesh.material;
  const bool material_valid = mesh.material >= 0 && static_cast<size_t>(mesh.material) < scene_->materials.size();
  const scenes::Material& material = material_valid ? scene_->materials[mesh.material] : default_material();
  const MaterialPoint mp = evaluate_material(*scene_, mesh, material, tri, bary, footprint(ray, hit.t, f.ng));
  apply_normal_map(mp, &f);
  // Both normals point to the side the ray arrived from.
  si.geometric_normal = si.front_face ? f.ng : -f.ng;
  si.shading_normal = si.front_face ? f.ns : -f.ns;
  si.tangent = f.tangent;
  si.shadow_lift = smooth_surface_point(mesh, tri, bary, si.position, si.geometric_normal) - si.position;

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

bool RenderScene::trace(const Ray& ray, SurfaceInteraction* si, Coverage coverage) const {
  Hit hit;
  if (!accelerator_.intersect(ray, &hit, coverage)) return false;
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
