#pragma once
// Attribute interpolation and material evaluation at a point of a triangle, written once
// and shared by RenderScene::interact, the emitter sampler (emissive textures) and the
// accelerator's alpha-mask filter, so the three always agree on UVs, texture transforms
// and alpha.
//
// A point is given by its triangle and barycentrics (b0, b1, b2), b0 = 1 - b1 - b2.
// Attribute arrays whose length differs from the position count are treated as absent.
// Texture slots whose index is out of range are treated as absent; untextured
// materials never touch a texture.
#include <glm/glm.hpp>

#include "phyir/render/brdf.h"
#include "phyir/scenes/scene.h"

namespace phyir::render {

// Barycentrics (b0, b1, b2) of the hit reported as (b1, b2).
inline glm::vec3 barycentrics(const glm::vec2& b12) { return glm::vec3(1.0f - b12.x - b12.y, b12.x, b12.y); }

// The UV a texture slot reads at the point: its TEXCOORD_n set (falling back to set 0,
// then to (0,0)) with the slot's KHR_texture_transform applied.
glm::vec2 slot_uv(const scenes::Mesh& mesh, const glm::uvec3& tri, const glm::vec3& bary,
                  const scenes::TextureSlot& slot);

// The surface area the pixel's ray cone covers at a hit (m^2; Ray::width and Ray::spread):
// textures are filtered to it. 0: no footprint, full resolution (rays without a cone: probe
// texels, light and shadow rays).
struct TextureFootprint {
  float area = 0.0f;
};

// The mip level at which a footprint of `area` m^2 covers one texel of `texture` through the
// slot's UV set on this triangle (its texels per m^2 from the triangle's UV and world areas,
// times the slot's transform scale); 0 without a footprint or for degenerate triangles.
float footprint_lod(const scenes::Mesh& mesh, const glm::uvec3& tri, const scenes::TextureSlot& slot,
                    const scenes::Texture& texture, const TextureFootprint& footprint);

// The slot's texel at the point (filtered to the footprint), or `absent` when the slot has
// no (valid) texture.
glm::vec4 sample_slot(const scenes::Scene& scene, const scenes::Mesh& mesh, const glm::uvec3& tri,
                      const glm::vec3& bary, const scenes::TextureSlot& slot, const glm::vec4& absent,
                      const TextureFootprint& footprint = {});

// Base-colour alpha at the point: factor.a x texture.a x COLOR_0.a (not clamped).
float material_alpha(const scenes::Scene& scene, const scenes::Mesh& mesh, const scenes::Material& material,
                     const glm::uvec3& tri, const glm::vec3& bary);

// The share of light a surface of this alpha stops (glTF 2.0, 3.9.4): OPAQUE 1, MASK 0 or 1
// by the cutoff, BLEND alpha clamped to [0, 1].
float coverage(const scenes::Material& material, float alpha);
// The same at a point of a triangle; 1 for OPAQUE without reading any texture.
float coverage_at(const scenes::Scene& scene, const scenes::Mesh& mesh, const scenes::Material& material,
                  const glm::uvec3& tri, const glm::vec3& bary);

// Emitted radiance of the front face at the point: emissive_factor x strength x emissive
// texture RGB (non-negative, finite).
glm::vec3 emitted_radiance(const scenes::Scene& scene, const scenes::Mesh& mesh,
                           const scenes::Material& material, const glm::uvec3& tri, const glm::vec3& bary);

// Everything the material says at a point, before any geometry-dependent step.
struct MaterialPoint {
  BrdfParams brdf;
  glm::vec3 emission{0.0f};   // front-face radiance, see emitted_radiance()
  float transmission = 0.0f;  // [0,1]
  float ior = 1.5f;
  float opacity = 1.0f;       // alpha after alphaMode: OPAQUE 1, MASK 0/1, BLEND alpha
  bool has_normal_map = false;
  glm::vec3 normal_ts{0.0f, 0.0f, 1.0f};  // tangent-space normal (scale applied, not normalised)
};

// Factors times textures, clamped to their ranges; never NaN.
MaterialPoint evaluate_material(const scenes::Scene& scene, const scenes::Mesh& mesh,
                                const scenes::Material& material, const glm::uvec3& tri, const glm::vec3& bary,
                                const TextureFootprint& footprint = {});

// The mean luminance of a texture's texels (the emitter sampler's power estimate of a
// textured emitter).
float mean_luminance(const scenes::Texture& texture);

}  // namespace phyir::render
