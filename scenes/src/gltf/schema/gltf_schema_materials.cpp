// Materials and textures (glTF 2.0 schema: material*, textureInfo, texture, sampler, image).
#include "gltf/schema/gltf_schema_objects.h"

namespace phyir::scenes::gltf::schema {

namespace {

constexpr long long kNearest = 9728, kLinear = 9729;

void check_normal_texture_info(const Object& info) {
  check_texture_info(info);
  info.number("scale");
}

void check_occlusion_texture_info(const Object& info) {
  check_texture_info(info);
  info.number("strength", unit_interval());
}

void check_pbr_metallic_roughness(const Object& pbr) {
  pbr.number_array("baseColorFactor", exactly(4), unit_interval());
  pbr.object("baseColorTexture", "textureInfo", check_texture_info);
  pbr.number("metallicFactor", unit_interval());
  pbr.number("roughnessFactor", unit_interval());
  pbr.object("metallicRoughnessTexture", "textureInfo", check_texture_info);
}

// The core enum is jpeg and png; texture-source extensions bring their own formats.
std::set<std::string> image_mime_types(const Document& document) {
  std::set<std::string> types = {"image/jpeg", "image/png"};
  const std::pair<const char*, const char*> by_extension[] = {{"EXT_texture_webp", "image/webp"},
                                                              {"KHR_texture_basisu", "image/ktx2"},
                                                              {"EXT_texture_avif", "image/avif"},
                                                              {"MSFT_texture_dds", "image/vnd-ms.dds"}};
  for (const auto& [extension, type] : by_extension)
    if (document.extensions_used.count(extension) != 0) types.insert(type);
  return types;
}

}  // namespace

void check_material(const Object& material) {
  material.object("pbrMetallicRoughness", "material.pbrMetallicRoughness", check_pbr_metallic_roughness);
  material.object("normalTexture", "material.normalTextureInfo", check_normal_texture_info);
  material.object("occlusionTexture", "material.occlusionTextureInfo", check_occlusion_texture_info);
  material.object("emissiveTexture", "textureInfo", check_texture_info);
  material.number_array("emissiveFactor", exactly(3), unit_interval());
  material.string_enum("alphaMode", {"OPAQUE", "MASK", "BLEND"});
  // alphaCutoff's schema dependency on alphaMode is not enforced: the spec says the cutoff
  // is ignored outside MASK, and the Khronos validator accepts it.
  material.number("alphaCutoff", at_least(0));
  material.boolean("doubleSided");
  check_material_extensions(material);
}

void check_texture_info(const Object& info) {
  info.required("index");
  info.index("index");
  info.integer("texCoord", at_least(0));
  check_texture_info_extensions(info);
}

void check_texture(const Object& texture) {
  texture.index("sampler");
  texture.index("source");
  check_texture_extensions(texture);
}

void check_sampler(const Object& sampler) {
  sampler.integer_enum("magFilter", {kNearest, kLinear});
  sampler.integer_enum("minFilter", {kNearest, kLinear, 9984, 9985, 9986, 9987});
  sampler.integer_enum("wrapS", {33071, 33648, 10497});
  sampler.integer_enum("wrapT", {33071, 33648, 10497});
}

void check_image(const Object& image) {
  image.string("uri");
  image.string_enum("mimeType", image_mime_types(image.document()));
  image.index("bufferView");
  image.depends_on("bufferView", "mimeType");
  image.forbid_together("uri", "bufferView");
  if (!image.has("uri") && !image.has("bufferView"))
    image.fail("", "has neither uri nor bufferView", "exactly one of them is required");
}

}  // namespace phyir::scenes::gltf::schema
