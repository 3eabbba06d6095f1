#include "phyir/insert/local_scene.h"

#include <algorithm>
#include <cmath>

#include "phyir/core/error.h"

namespace phyir::insert {

namespace {

constexpr float kRestLift = 5e-4f;  // metres: the object sits on the disc, not in it
constexpr int kDiscSegments = 64;

void shift_slot(scenes::TextureSlot* slot, int offset) {
  if (slot->present()) slot->texture += offset;
}

}  // namespace

scenes::Scene place_object(const scenes::Scene& object, const SurfacePoint& ground, const Placement& placement) {
  const scenes::Bounds b = object.compute_bounds();
  if (b.empty()) fail("{}: the object has no triangles to insert", object.source);
  const glm::vec3 foot((b.min.x + b.max.x) * 0.5f, b.min.y, (b.min.z + b.max.z) * 0.5f);
  const float c = std::cos(placement.yaw), s = std::sin(placement.yaw);
  auto rotate = [&](const glm::vec3& v) { return glm::vec3(c * v.x + s * v.z, v.y, -s * v.x + c * v.z); };
  const glm::vec3 origin = ground.position + glm::vec3(0.0f, kRestLift, 0.0f);
  scenes::Scene placed;
  placed.source = object.source;
  placed.materials = object.materials;
  placed.textures = object.textures;
  placed.meshes = object.meshes;
  for (scenes::Mesh& m : placed.meshes) {
    for (glm::vec3& p : m.positions) p = origin + placement.scale * rotate(p - foot);
    for (glm::vec3& n : m.normals) n = rotate(n);
    for (glm::vec4& t : m.tangents) t = glm::vec4(rotate(glm::vec3(t)), t.w);
  }
  placed.bounds = placed.compute_bounds();
  return placed;
}

scenes::Scene support_disc(const SurfacePoint& ground, float radius) {
  scenes::Scene disc;
  disc.source = "phyir insert: support surface";
  scenes::Material m;
  m.name = "support surface";
  m.base_color_factor = glm::vec4(glm::clamp(ground.base_color, 0.0f, 1.0f), 1.0f);
  m.roughness_factor = std::clamp(ground.roughness, 0.0f, 1.0f);
  m.metallic_factor = std::clamp(ground.metalness, 0.0f, 1.0f);
  disc.materials.push_back(m);
  const glm::vec3 n = ground.normal;
  const glm::vec3 helper = std::abs(n.y) < 0.9f ? glm::vec3(0, 1, 0) : glm::vec3(1, 0, 0);
  const glm::vec3 t = glm::normalize(glm::cross(helper, n)), bt = glm::cross(n, t);
  scenes::Mesh mesh;
  mesh.name = "support surface";
  mesh.positions.push_back(ground.position);
  mesh.normals.push_back(n);
  for (int k = 0; k < kDiscSegments; ++k) {
    const float a = 2.0f * float(M_PI) * float(k) / kDiscSegments;
    mesh.positions.push_back(ground.position + radius * (std::cos(a) * t + std::sin(a) * bt));
    mesh.normals.push_back(n);
  }
  // Counter-clockwise seen from the normal's side (t x bt = n).
  for (unsigned k = 0; k < unsigned(kDiscSegments); ++k)
    mesh.triangles.emplace_back(0u, 1u + k, 1u + (k + 1) % unsigned(kDiscSegments));
  disc.meshes.push_back(std::move(mesh));
  disc.bounds = disc.compute_bounds();
  return disc;
}

scenes::Scene merge_scenes(const scenes::Scene& a, const scenes::Scene& b) {
  scenes::Scene out = a;
  const int material_offset = int(a.materials.size()), texture_offset = int(a.textures.size());
  for (scenes::Material m : b.materials) {
    for (scenes::TextureSlot* slot : {&m.base_color_texture, &m.metallic_roughness_texture, &m.normal_texture,
                                      &m.emissive_texture, &m.transmission_texture})
      shift_slot(slot, texture_offset);
    out.materials.push_back(std::move(m));
  }
  out.textures.insert(out.textures.end(), b.textures.begin(), b.textures.end());
  for (scenes::Mesh m : b.meshes) {
    m.material += material_offset;
    out.meshes.push_back(std::move(m));
  }
  out.bounds = out.compute_bounds();
  return out;
}

float disc_radius_for(const scenes::Scene& placed, const SurfacePoint& ground) {
  const scenes::Bounds b = placed.compute_bounds();
  if (b.empty()) return kMinDiscRadius;
  const glm::vec3 half = 0.5f * (b.max - b.min);
  const float height = b.max.y - ground.position.y;
  return std::max(kMinDiscRadius, kDiscRadiusFactor * std::max({half.x, half.z, 0.5f * height}));
}

}  // namespace phyir::insert
