#pragma once
// Wavefront MTL materials and their mapping to glTF's metal-roughness model. The rules and
// their reasons are in docs/assets.md ("From MTL to metal-roughness"); the function is pure
// so that the table there is what the tests check.
#include <glm/glm.hpp>

#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace phyir::scenes {

// An MTL material as written: absent statements stay empty (tinyobjloader alone cannot tell
// a written 0 from a default one). Colours are as stored (display-referred values).
struct MtlMaterial {
  std::string name;
  std::optional<glm::vec3> Kd, Ks, Ke;
  std::optional<float> Ns, d, Tr, Ni, Pr, Pm;
  std::optional<int> illum;
  // Texture statements: tinyobjloader's file name (options parsed away) and the whole
  // argument as written (file names with spaces survive only there). Empty when absent.
  std::string map_Kd, map_Kd_raw;
  std::string map_d, map_d_raw;
};

// Materials of one MTL text, in file order. `source` names the file in warnings.
// Lines tinyobjloader cannot read are skipped (it never fails); warnings are appended.
std::vector<MtlMaterial> parse_mtl(std::string_view text, const std::string& source,
                                   std::vector<std::string>* warnings = nullptr);

enum class AssetAlphaMode { Opaque, Mask, Blend };

// A glTF-style metal-roughness material. Textures are indices into AssetModel::textures.
struct AssetMaterial {
  std::string name;
  glm::vec3 base_color{1.0f};    // linear; white when a base colour texture replaces Kd
  float roughness = 1.0f;        // perceptual (GGX alpha = roughness^2)
  float metallic = 0.0f;
  float transmission = 0.0f;     // KHR_materials_transmission
  float ior = 1.5f;              // KHR_materials_ior
  float alpha = 1.0f;            // coverage (opacity) when not transmissive
  AssetAlphaMode alpha_mode = AssetAlphaMode::Opaque;
  // OBJ has no back-face rule and many models are single sheets (leaves, curtains, glass
  // panes) or inconsistently wound, so every material is double-sided.
  bool double_sided = true;
  int base_color_texture = -1;   // sRGB-encoded image; its alpha, if any, is coverage
  int alpha_texture = -1;        // map_d: coverage in the image's first channel
};

// The mapping of docs/assets.md. `has_base_color_texture` and `has_alpha_texture` say
// whether map_Kd / map_d were found (an unresolved texture leaves Kd as the colour); texture
// indices are left at -1 for the caller to fill.
AssetMaterial metal_roughness_from_mtl(const MtlMaterial& mtl, bool has_base_color_texture = false,
                                       bool has_alpha_texture = false);

// The Blinn-Phong exponent's GGX equivalent: alpha = sqrt(2 / (Ns + 2)) (Walter et al. 2007,
// "Microfacet models for refraction", section 5.2), roughness = sqrt(alpha).
float roughness_from_phong_exponent(float ns);

// The sRGB transfer function's inverse (IEC 61966-2-1), per channel, input clamped to [0, 1].
glm::vec3 srgb_colour_to_linear(glm::vec3 encoded);

}  // namespace phyir::scenes
