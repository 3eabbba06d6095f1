#include "gltf/read/gltf_materials.h"

#include <fmt/ranges.h>

#include <algorithm>
#include <cmath>
#include <set>

#include "gltf/read/gltf_values.h"

namespace phyir::scenes::gltf {

namespace {

constexpr const char* kTextureTransform = "KHR_texture_transform";
constexpr const char* kEmissiveStrength = "KHR_materials_emissive_strength";
constexpr const char* kTransmission = "KHR_materials_transmission";
constexpr const char* kIor = "KHR_materials_ior";
constexpr const char* kSpecular = "KHR_materials_specular";

// A textureInfo, from tinygltf's parsed struct or from an extension's JSON.
struct TextureRef {
  int index = -1;
  int texcoord = 0;
  const tinygltf::Value* transform = nullptr;  // the KHR_texture_transform object
};

const tinygltf::Value* find_extension(const tinygltf::ExtensionMap& extensions, const std::string& name) {
  const auto it = extensions.find(name);
  return it != extensions.end() ? &it->second : nullptr;
}

template <typename Info>
TextureRef ref_from_info(const Info& info) {
  return {info.index, info.texCoord, find_extension(info.extensions, kTextureTransform)};
}

class MaterialConverter {
 public:
  MaterialConverter(const GltfContext& ctx, TextureTable& textures, int index)
      : ctx_(ctx),
        textures_(textures),
        source_(ctx.model.materials[static_cast<size_t>(index)]),
        where_(label("material", index, ctx.model.materials)) {}

  Material convert() {
    Material m;
    m.name = source_.name;
    convert_core(m);
    convert_extensions(m);
    for (const auto& [name, value] : source_.extensions) used_.insert(name);
    m.extensions.assign(used_.begin(), used_.end());
    return m;
  }

 private:
  void convert_core(Material& m) {
    const tinygltf::PbrMetallicRoughness& pbr = source_.pbrMetallicRoughness;
    const std::vector<double> base = checked_numbers(pbr.baseColorFactor, 4, "baseColorFactor");
    m.base_color_factor = glm::vec4(base[0], base[1], base[2], base[3]);
    m.base_color_texture =
        slot(ref_from_info(pbr.baseColorTexture), TextureEncoding::SrgbColour, "baseColorTexture");
    m.metallic_factor = std::clamp(checked_number(pbr.metallicFactor, "metallicFactor"), 0.0f, 1.0f);
    m.roughness_factor = std::clamp(checked_number(pbr.roughnessFactor, "roughnessFactor"), 0.0f, 1.0f);
    m.metallic_roughness_texture = slot(ref_from_info(pbr.metallicRoughnessTexture),
                                        TextureEncoding::LinearData, "metallicRoughnessTexture");
    m.normal_texture =
        slot(ref_from_info(source_.normalTexture), TextureEncoding::LinearData, "normalTexture");
    m.normal_scale = checked_number(source_.normalTexture.scale, "normalTexture.scale");
    const std::vector<double> emissive = checked_numbers(source_.emissiveFactor, 3, "emissiveFactor");
    m.emissive_factor = glm::max(glm::vec3(emissive[0], emissive[1], emissive[2]), glm::vec3(0.0f));
    m.emissive_texture =
        slot(ref_from_info(source_.emissiveTexture), TextureEncoding::SrgbColour, "emissiveTexture");
    m.alpha_mode = alpha_mode(source_.alphaMode);
    m.alpha_cutoff = checked_number(source_.alphaCutoff, "alphaCutoff");
    m.double_sided = source_.doubleSided;
  }

  void convert_extensions(Material& m) {
    if (const tinygltf::Value* e = find_extension(source_.extensions, kEmissiveStrength)) {
      const std::string where = where_ + " " + kEmissiveStrength;
      m.emissive_strength = number_member(ctx_, *e, "emissiveStrength", where).value_or(1.0f);
      if (m.emissive_strength < 0.0f)
        ctx_.fail("{} emissiveStrength {} is negative", where, m.emissive_strength);
    }
    if (const tinygltf::Value* e = find_extension(source_.extensions, kTransmission)) {
      const std::string where = where_ + " " + kTransmission;
      m.transmission_factor =
          std::clamp(number_member(ctx_, *e, "transmissionFactor", where).value_or(0.0f), 0.0f, 1.0f);
      if (const tinygltf::Value* info = member(*e, "transmissionTexture"))
        m.transmission_texture = slot(ref_from_value(*info, where + " transmissionTexture"),
                                      TextureEncoding::LinearData, "transmissionTexture");
    }
    if (const tinygltf::Value* e = find_extension(source_.extensions, kIor)) {
      const std::string where = where_ + " " + kIor;
      const float ior = number_member(ctx_, *e, "ior", where).value_or(1.5f);
      if (ior >= 1.0f) {
        m.ior = ior;
      } else {
        ctx_.warn("{} ior {} is below 1: the default 1.5 is used", where, ior);
      }
    }
    if (const tinygltf::Value* e = find_extension(source_.extensions, kSpecular)) check_specular(*e);
  }

  // The model's dielectric F0 is fixed at 0.04 (docs/brdf.md). Blender writes this
  // extension on every material, mostly with its defaults, which change nothing: those
  // pass silently; other values are ignored with a warning naming them.
  void check_specular(const tinygltf::Value& e) {
    const std::string where = where_ + " " + kSpecular;
    std::vector<std::string> ignored;
    const float factor = number_member(ctx_, e, "specularFactor", where).value_or(1.0f);
    if (factor != 1.0f) ignored.push_back(fmt::format("specularFactor {}", factor));
    if (const tinygltf::Value* value = member(e, "specularColorFactor")) {
      const std::optional<glm::vec3> color = as_vec3(*value);
      if (!color) ctx_.fail("{} specularColorFactor is not an array of three finite numbers", where);
      if (*color != glm::vec3(1.0f))
        ignored.push_back(fmt::format("specularColorFactor [{}, {}, {}]", color->x, color->y, color->z));
    }
    for (const char* texture : {"specularTexture", "specularColorTexture"})
      if (member(e, texture) != nullptr) ignored.emplace_back(texture);
    if (!ignored.empty())
      ctx_.warn("{} {} ignored: the dielectric F0 stays 0.04 (docs/brdf.md)", where, fmt::join(ignored, ", "));
  }

  TextureRef ref_from_value(const tinygltf::Value& info, const std::string& where) {
    TextureRef ref;
    const auto index = integer_member(ctx_, info, "index", where);
    if (!index) ctx_.fail("{} has no index", where);
    ref.index = *index;
    ref.texcoord = integer_member(ctx_, info, "texCoord", where).value_or(0);
    if (const tinygltf::Value* extensions = member(info, "extensions"))
      ref.transform = member(*extensions, kTextureTransform);
    return ref;
  }

  TextureSlot slot(const TextureRef& ref, TextureEncoding encoding, const std::string& property) {
    TextureSlot slot;
    if (ref.index < 0) return slot;
    const std::string where = where_ + " " + property;
    slot.texture = textures_.get(ref.index, encoding, where);
    int texcoord = ref.texcoord;
    if (ref.transform != nullptr) {
      used_.insert(kTextureTransform);
      const std::string transform_where = where + " " + kTextureTransform;
      slot.transform.offset =
          vec2_member(ctx_, *ref.transform, "offset", transform_where).value_or(glm::vec2(0.0f));
      slot.transform.scale =
          vec2_member(ctx_, *ref.transform, "scale", transform_where).value_or(glm::vec2(1.0f));
      slot.transform.rotation =
          number_member(ctx_, *ref.transform, "rotation", transform_where).value_or(0.0f);
      texcoord = integer_member(ctx_, *ref.transform, "texCoord", transform_where).value_or(texcoord);
    }
    if (texcoord < 0) ctx_.fail("{} texCoord {} is negative", where, texcoord);
    if (texcoord > 1) {
      ctx_.warn("{} uses TEXCOORD_{}: only TEXCOORD_0 and TEXCOORD_1 are kept, TEXCOORD_0 used", where,
                texcoord);
      texcoord = 0;
    }
    slot.texcoord = texcoord;
    return slot;
  }

  AlphaMode alpha_mode(const std::string& mode) {
    if (mode == "OPAQUE" || mode.empty()) return AlphaMode::Opaque;
    if (mode == "MASK") return AlphaMode::Mask;
    if (mode == "BLEND") return AlphaMode::Blend;
    ctx_.warn("{} alphaMode '{}' is unknown: OPAQUE used", where_, mode);
    return AlphaMode::Opaque;
  }

  float checked_number(double value, const char* property) {
    // Beyond float's range (JSON allows 1e300) the conversion would be undefined: refused too.
    const std::optional<float> f = to_finite_float(value);
    if (!f) ctx_.fail("{} {} is not a finite number ({})", where_, property, value);
    return *f;
  }

  std::vector<double> checked_numbers(const std::vector<double>& values, size_t count, const char* property) {
    if (values.size() != count)
      ctx_.fail("{} {} has {} numbers, expected {}", where_, property, values.size(), count);
    for (double v : values) checked_number(v, property);
    return values;
  }

  const GltfContext& ctx_;
  TextureTable& textures_;
  const tinygltf::Material& source_;
  const std::string where_;
  std::set<std::string> used_;  // extensions this material uses, for Material::extensions
};

}  // namespace

std::vector<Material> convert_materials(const GltfContext& ctx, TextureTable& textures) {
  std::vector<Material> materials;
  for (size_t i = 0; i < ctx.model.materials.size(); ++i)
    materials.push_back(MaterialConverter(ctx, textures, static_cast<int>(i)).convert());
  return materials;
}

Material default_material() {
  Material m;
  m.name = "default";
  m.base_color_factor = glm::vec4(1.0f);
  m.metallic_factor = 1.0f;
  m.roughness_factor = 1.0f;
  return m;
}

}  // namespace phyir::scenes::gltf
