#include "gltf/write/gltf_write_materials.h"

#include <cmath>

#include "gltf/write/gltf_write_values.h"
#include "phyir/core/error.h"

namespace phyir::scenes::gltf_write {

namespace {

using nlohmann::json;

// {"index": i} plus KHR_texture_transform when the transform is set and not the identity.
json texture_info(const GltfTextureRef& ref, const GltfDocument& doc, const GltfMaterial& m,
                  std::set<std::string>& extensions) {
  if (ref.texture >= static_cast<int>(doc.textures.size())) {
    fail("glTF writer: material '{}' uses texture {} of {}", m.name, ref.texture, doc.textures.size());
  }
  json info = {{"index", ref.texture}};
  if (!ref.transform || ref.transform->is_identity()) return info;
  const TextureTransform& t = *ref.transform;
  json transform = json::object();
  if (t.offset != glm::vec2(0.0f)) transform["offset"] = tidy_array(&t.offset[0], 2);
  if (t.rotation != 0.0f) transform["rotation"] = tidy(t.rotation);
  if (t.scale != glm::vec2(1.0f)) transform["scale"] = tidy_array(&t.scale[0], 2);
  info["extensions"] = {{"KHR_texture_transform", transform}};
  extensions.insert("KHR_texture_transform");
  return info;
}

const char* alpha_mode_name(AlphaMode mode) {
  switch (mode) {
    case AlphaMode::Mask: return "MASK";
    case AlphaMode::Blend: return "BLEND";
    case AlphaMode::Opaque: break;
  }
  return "OPAQUE";
}

json pbr_json(const GltfMaterial& m, const GltfDocument& doc, std::set<std::string>& extensions) {
  json pbr = {{"baseColorFactor", tidy_array(&m.base_color_factor[0], 4)},
              {"metallicFactor", tidy(m.metallic_factor)},
              {"roughnessFactor", tidy(m.roughness_factor)}};
  if (m.base_color_texture.present()) pbr["baseColorTexture"] = texture_info(m.base_color_texture, doc, m, extensions);
  if (m.metallic_roughness_texture.present())
    pbr["metallicRoughnessTexture"] = texture_info(m.metallic_roughness_texture, doc, m, extensions);
  return pbr;
}

// KHR_materials_*: emissive strength, transmission, ior.
json material_extensions(const GltfMaterial& m) {
  json ext = json::object();
  if (m.emissive_strength != 1.0f) {
    ext["KHR_materials_emissive_strength"] = {{"emissiveStrength", tidy(m.emissive_strength)}};
  }
  if (m.transmission_factor > 0.0f) {
    ext["KHR_materials_transmission"] = {{"transmissionFactor", tidy(m.transmission_factor)}};
  }
  if (m.ior) ext["KHR_materials_ior"] = {{"ior", tidy(*m.ior)}};
  return ext;
}

void check_alpha(const GltfMaterial& m) {
  if (m.alpha_mode == AlphaMode::Mask && !(m.alpha_cutoff >= 0.0f && std::isfinite(m.alpha_cutoff)))
    fail("glTF writer: material '{}' alpha_cutoff is {}: must be a finite number >= 0", m.name, m.alpha_cutoff);
}

}  // namespace

bool uses_textures(const GltfMaterial& m) {
  return m.base_color_texture.present() || m.metallic_roughness_texture.present() || m.normal_texture.present() ||
         m.emissive_texture.present();
}

json encode_material(const GltfMaterial& m, const GltfDocument& doc, std::set<std::string>& extensions) {
  check_alpha(m);
  json out = {{"name", m.name}, {"pbrMetallicRoughness", pbr_json(m, doc, extensions)}};
  if (m.normal_texture.present()) {
    out["normalTexture"] = texture_info(m.normal_texture, doc, m, extensions);
    if (m.normal_scale != 1.0f) out["normalTexture"]["scale"] = tidy(m.normal_scale);
  }
  if (m.emissive_factor != glm::vec3(0.0f)) out["emissiveFactor"] = tidy_array(&m.emissive_factor[0], 3);
  if (m.emissive_texture.present()) out["emissiveTexture"] = texture_info(m.emissive_texture, doc, m, extensions);
  if (m.alpha_mode != AlphaMode::Opaque) out["alphaMode"] = alpha_mode_name(m.alpha_mode);
  if (m.alpha_mode == AlphaMode::Mask && m.alpha_cutoff != 0.5f) out["alphaCutoff"] = tidy(m.alpha_cutoff);
  if (m.double_sided) out["doubleSided"] = true;
  const json ext = material_extensions(m);
  for (const auto& item : ext.items()) extensions.insert(item.key());
  if (!ext.empty()) out["extensions"] = ext;
  return out;
}

}  // namespace phyir::scenes::gltf_write
