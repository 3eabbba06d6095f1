#include "phyir/render/material_eval.h"

#include <cmath>

#include "phyir/core/safe_math.h"

namespace phyir::render {

namespace {

template <typename T>
bool has_attribute(const std::vector<T>& attribute, const scenes::Mesh& mesh) {
  return !attribute.empty() && attribute.size() == mesh.positions.size();
}

template <typename T>
T interpolate(const std::vector<T>& a, const glm::uvec3& tri, const glm::vec3& b) {
  return a[tri.x] * b.x + a[tri.y] * b.y + a[tri.z] * b.z;
}

bool slot_valid(const scenes::Scene& scene, const scenes::TextureSlot& slot) {
  return slot.present() && static_cast<size_t>(slot.texture) < scene.textures.size();
}

// Non-finite channels become `fallback`; the texture loader should never produce them,
// but one bad texel must not turn a whole render into NaN.
glm::vec4 finite_or(const glm::vec4& v, float fallback) {
  glm::vec4 r = v;
  for (int i = 0; i < 4; ++i) r[i] = phyir::finite_or(r[i], fallback);
  return r;
}

}  // namespace

glm::vec2 slot_uv(const scenes::Mesh& mesh, const glm::uvec3& tri, const glm::vec3& bary,
                  const scenes::TextureSlot& slot) {
  glm::vec2 uv(0.0f);
  if (slot.texcoord == 1 && has_attribute(mesh.texcoords1, mesh)) {
    uv = interpolate(mesh.texcoords1, tri, bary);
  } else if (has_attribute(mesh.texcoords0, mesh)) {
    uv = interpolate(mesh.texcoords0, tri, bary);
  }
  return slot.transform.is_identity() ? uv : slot.transform.apply(uv);
}

float footprint_lod(const scenes::Mesh& mesh, const glm::uvec3& tri, const scenes::TextureSlot& slot,
                    const scenes::Texture& texture, const TextureFootprint& footprint) {
  if (!(footprint.area > 0.0f) || texture.levels() < 2) return 0.0f;
  const std::vector<glm::vec2>& uvs = slot.texcoord == 1 && has_attribute(mesh.texcoords1, mesh) ? mesh.texcoords1
                                                                                                 : mesh.texcoords0;
  if (!has_attribute(uvs, mesh)) return 0.0f;
  const glm::vec3& p0 = mesh.positions[tri.x];
  const float world_area2 = glm::length(glm::cross(mesh.positions[tri.y] - p0, mesh.positions[tri.z] - p0));
  const glm::vec2 a = uvs[tri.y] - uvs[tri.x], b = uvs[tri.z] - uvs[tri.x];
  const float uv_area2 = std::abs(a.x * b.y - a.y * b.x) * std::abs(slot.transform.scale.x * slot.transform.scale.y);
  const float texels_per_m2 = uv_area2 * float(texture.width()) * float(texture.height()) / world_area2;
  const float lod = 0.5f * std::log2(texels_per_m2 * footprint.area);
  return std::isfinite(lod) ? std::max(lod, 0.0f) : 0.0f;
}

glm::vec4 sample_slot(const scenes::Scene& scene, const scenes::Mesh& mesh, const glm::uvec3& tri,
                      const glm::vec3& bary, const scenes::TextureSlot& slot, const glm::vec4& absent,
                      const TextureFootprint& footprint) {
  if (!slot_valid(scene, slot)) return absent;
  const scenes::Texture& texture = scene.textures[slot.texture];
  const glm::vec2 uv = slot_uv(mesh, tri, bary, slot);
  if (!(footprint.area > 0.0f)) return finite_or(texture.sample(uv), 0.0f);
  return finite_or(texture.sample(uv, footprint_lod(mesh, tri, slot, texture, footprint)), 0.0f);
}

float material_alpha(const scenes::Scene& scene, const scenes::Mesh& mesh, const scenes::Material& material,
                     const glm::uvec3& tri, const glm::vec3& bary) {
  float alpha = material.base_color_factor.w;
  if (slot_valid(scene, material.base_color_texture))
    alpha *= sample_slot(scene, mesh, tri, bary, material.base_color_texture, glm::vec4(1.0f)).w;
  if (has_attribute(mesh.colors, mesh)) alpha *= interpolate(mesh.colors, tri, bary).w;
  return phyir::finite_or(alpha, 1.0f);
}

float coverage(const scenes::Material& material, float alpha) {
  switch (material.alpha_mode) {
    case scenes::AlphaMode::Mask: return alpha >= material.alpha_cutoff ? 1.0f : 0.0f;
    case scenes::AlphaMode::Blend: return clamp01(alpha);
    default: return 1.0f;
  }
}

float coverage_at(const scenes::Scene& scene, const scenes::Mesh& mesh, const scenes::Material& material,
                  const glm::uvec3& tri, const glm::vec3& bary) {
  if (material.alpha_mode == scenes::AlphaMode::Opaque) return 1.0f;
  return coverage(material, material_alpha(scene, mesh, material, tri, bary));
}

glm::vec3 emitted_radiance(const scenes::Scene& scene, const scenes::Mesh& mesh,
                           const scenes::Material& material, const glm::uvec3& tri, const glm::vec3& bary) {
  glm::vec3 e = material.emission();
  if (!material.is_emissive()) return glm::vec3(0.0f);
  if (slot_valid(scene, material.emissive_texture))
    e *= glm::vec3(sample_slot(scene, mesh, tri, bary, material.emissive_texture, glm::vec4(1.0f)));
  e = glm::max(e, glm::vec3(0.0f));
  return is_finite(e) ? e : glm::vec3(0.0f);
}

MaterialPoint evaluate_material(const scenes::Scene& scene, const scenes::Mesh& mesh,
                                const scenes::Material& material, const glm::uvec3& tri, const glm::vec3& bary,
                                const TextureFootprint& footprint) {
  MaterialPoint m;

  // Base colour: factor x texture x COLOR_0 (glTF 2.0, 3.9.2).
  glm::vec4 base = finite_or(material.base_color_factor, 1.0f);
  if (slot_valid(scene, material.base_color_texture))
    // A MASK cut-out follows the full-resolution alpha the accelerator tests.
    base *= sample_slot(scene, mesh, tri, bary, material.base_color_texture, glm::vec4(1.0f),
                        material.alpha_mode == scenes::AlphaMode::Mask ? TextureFootprint{} : footprint);
  if (has_attribute(mesh.colors, mesh)) base *= finite_or(interpolate(mesh.colors, tri, bary), 1.0f);
  m.brdf.base_color = glm::clamp(glm::vec3(base), glm::vec3(0.0f), glm::vec3(1.0f));

  // Metallic-roughness: G = roughness, B = metalness.
  float roughness = material.roughness_factor, metalness = material.metallic_factor;
  if (slot_valid(scene, material.metallic_roughness_texture)) {
    const glm::vec4 mr =
        sample_slot(scene, mesh, tri, bary, material.metallic_roughness_texture, glm::vec4(1.0f), footprint);
    roughness *= mr.y;  // G
    metalness *= mr.z;  // B
  }
  m.brdf.roughness = clamp01(phyir::finite_or(roughness, 1.0f));
  m.brdf.metalness = clamp01(phyir::finite_or(metalness, 0.0f));

  m.emission = emitted_radiance(scene, mesh, material, tri, bary);

  float transmission = material.transmission_factor;
  if (slot_valid(scene, material.transmission_texture))
    transmission *= sample_slot(scene, mesh, tri, bary, material.transmission_texture, glm::vec4(1.0f), footprint).x;  // R
  m.transmission = clamp01(phyir::finite_or(transmission, 0.0f));
  m.ior = (std::isfinite(material.ior) && material.ior >= 1.0f) ? material.ior : 1.5f;

  m.opacity = coverage(material, phyir::finite_or(base.w, 1.0f));

  // Tangent-space normal: (texel * 2 - 1) * (scale, scale, 1) (glTF 2.0, 3.9.3).
  if (slot_valid(scene, material.normal_texture)) {
    const glm::vec4 t = sample_slot(scene, mesh, tri, bary, material.normal_texture, glm::vec4(0.5f, 0.5f, 1.0f, 1.0f), footprint);
    const float scale = phyir::finite_or(material.normal_scale, 1.0f);
    m.normal_ts = (glm::vec3(t) * 2.0f - glm::vec3(1.0f)) * glm::vec3(scale, scale, 1.0f);
    m.has_normal_map = true;
  }
  return m;
}

float mean_luminance(const scenes::Texture& texture) {
  if (!texture.has_texels()) return 1.0f;  // Texture::sample returns 1 for an empty texture
  double sum = 0.0;
  for (int y = 0; y < texture.height(); ++y)
    for (int x = 0; x < texture.width(); ++x) {
      const float l = luminance(glm::max(glm::vec3(texture.texel(x, y)), glm::vec3(0.0f)));
      if (std::isfinite(l)) sum += l;
    }
  return static_cast<float>(sum / static_cast<double>(texture.texel_count()));
}

}  // namespace phyir::render
