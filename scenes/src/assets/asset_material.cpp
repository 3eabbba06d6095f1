// metal_roughness_from_mtl: the MTL -> metal-roughness table of docs/assets.md. Sweet Home
// 3D shows these materials with Java 3D's Phong shading; the rules keep what it shows
// (Kd replaced by map_Kd, illum 0/1 without highlight, d as see-through) in PBR terms.
#include <algorithm>
#include <cmath>

#include "phyir/scenes/asset_material.h"

namespace phyir::scenes {

namespace {

// Ks below this is black: no highlight, whatever Ns says.
constexpr float kNoSpecular = 0.01f;
// Java 3D's default shininess, which Sweet Home 3D keeps when a material has no Ns.
constexpr float kJava3dShininess = 64.0f;
// A colour is "coloured" when (max - min) / max reaches this: Blender's greys differ by
// rounding only, while gold, copper or brass specular colours reach 0.4-0.9.
constexpr float kColouredSaturation = 0.2f;
// Rule A: a coloured specular at least this strong (and stronger than Kd) is a metal's F0.
constexpr float kMetalSpecular = 0.5f;
// Rule B: a mirror-like grey material. Ns >= 500 is GGX roughness <= 0.25; Ks >= 0.9 a
// near-total reflection; Kd at most 3/4 of Ks.
constexpr float kMirrorExponent = 500.0f;
constexpr float kMirrorSpecular = 0.9f;
constexpr float kMirrorDiffuseRatio = 0.75f;
// Ni = 1 is what Blender and most exporters write when nothing was set; glass is 1.5.
constexpr float kDefaultIor = 1.5f;
// Nothing solid or liquid in a home has an index below 1.1 (water 1.33): lower values
// (1.0, and the 1.02 some exporters write for glass) mean "not set".
constexpr float kMinIor = 1.1f;
constexpr float kMaxIor = 3.0f;     // beyond diamond (2.42): a typo or a non-optical value
// Opacity above this is opaque (MTL files print d with 6 decimals).
constexpr float kOpaque = 0.999f;

float max_of(glm::vec3 c) { return std::max({c.x, c.y, c.z}); }

float saturation(glm::vec3 c) {
  const float high = max_of(c);
  return high > 0.0f ? (high - std::min({c.x, c.y, c.z})) / high : 0.0f;
}

glm::vec3 clamp01(glm::vec3 c) { return glm::clamp(c, glm::vec3(0.0f), glm::vec3(1.0f)); }

bool is_glass_model(int illum) { return illum == 4 || illum == 6 || illum == 7 || illum == 9; }

float opacity(const MtlMaterial& m) {
  if (m.d) return std::clamp(*m.d, 0.0f, 1.0f);
  if (m.Tr) return std::clamp(1.0f - *m.Tr, 0.0f, 1.0f);
  return 1.0f;
}

bool has_highlight(const MtlMaterial& m) {
  return m.illum.value_or(2) >= 2 && max_of(m.Ks.value_or(glm::vec3(0.0f))) > kNoSpecular;
}

float roughness(const MtlMaterial& m) {
  if (m.Pr) return std::clamp(*m.Pr, 0.0f, 1.0f);
  if (!has_highlight(m)) return 1.0f;
  return roughness_from_phong_exponent(m.Ns.value_or(kJava3dShininess));
}

// 1 for a metal recognised from Ks against Kd (rules A and B of docs/assets.md), else 0.
bool looks_metallic(const MtlMaterial& m) {
  if (!has_highlight(m)) return false;
  const glm::vec3 ks = *m.Ks;
  const glm::vec3 kd = m.Kd.value_or(glm::vec3(1.0f));
  const bool coloured_specular =
      saturation(ks) >= kColouredSaturation && max_of(ks) >= kMetalSpecular && max_of(ks) >= max_of(kd);
  const bool mirror = m.Ns.value_or(0.0f) >= kMirrorExponent && max_of(ks) >= kMirrorSpecular &&
                      saturation(kd) < kColouredSaturation && max_of(kd) <= kMirrorDiffuseRatio * max_of(ks);
  return coloured_specular || mirror;
}

float ior(const MtlMaterial& m) {
  if (m.Ni && *m.Ni >= kMinIor && *m.Ni <= kMaxIor) return *m.Ni;
  return kDefaultIor;
}

// See-through part: glass (transmission) or coverage (alpha).
void apply_opacity(const MtlMaterial& m, bool has_base_color_texture, bool has_alpha_texture, AssetMaterial& out) {
  const float o = opacity(m);
  const int illum = m.illum.value_or(2);
  if (o < kOpaque) {
    const bool coverage = !is_glass_model(illum) && (illum <= 1 || has_base_color_texture || has_alpha_texture);
    if (coverage) {
      out.alpha = o;
      out.alpha_mode = AssetAlphaMode::Blend;
    } else {
      out.transmission = 1.0f - o;
      out.metallic = 0.0f;
    }
  }
  if (has_alpha_texture) out.alpha_mode = AssetAlphaMode::Blend;
}

}  // namespace

float roughness_from_phong_exponent(float ns) {
  const float alpha = std::sqrt(2.0f / (std::max(ns, 0.0f) + 2.0f));
  return std::sqrt(alpha);
}

glm::vec3 srgb_colour_to_linear(glm::vec3 encoded) {
  glm::vec3 linear;
  for (int i = 0; i < 3; ++i) {
    const float c = std::clamp(encoded[i], 0.0f, 1.0f);
    linear[i] = c <= 0.04045f ? c / 12.92f : std::pow((c + 0.055f) / 1.055f, 2.4f);
  }
  return linear;
}

AssetMaterial metal_roughness_from_mtl(const MtlMaterial& m, bool has_base_color_texture, bool has_alpha_texture) {
  AssetMaterial out;
  out.name = m.name;
  out.roughness = roughness(m);
  out.ior = ior(m);
  const bool metal_from_specular = !m.Pm && looks_metallic(m);
  out.metallic = m.Pm ? std::clamp(*m.Pm, 0.0f, 1.0f) : (metal_from_specular ? 1.0f : 0.0f);
  if (has_base_color_texture) {
    out.base_color = glm::vec3(1.0f);  // Sweet Home 3D draws the texture instead of Kd
  } else if (metal_from_specular) {
    const glm::vec3 ks = *m.Ks;  // the hue of the reflection: Phong's Ks scales a highlight
    out.base_color = srgb_colour_to_linear(ks / max_of(ks));
  } else {
    out.base_color = srgb_colour_to_linear(clamp01(m.Kd.value_or(glm::vec3(1.0f))));
  }
  apply_opacity(m, has_base_color_texture, has_alpha_texture, out);
  return out;
}

}  // namespace phyir::scenes
