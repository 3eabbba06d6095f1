// The schemas of the extensions the loader reads (and of the compression and instancing
// extensions it must recognise before refusing or falling back), from
// github.com/KhronosGroup/glTF extensions/2.0/{Khronos,Vendor}/<name>/schema.
#include <fmt/format.h>

#include <cmath>

#include "gltf/schema/gltf_schema_objects.h"

namespace phyir::scenes::gltf::schema {

namespace {

constexpr double kHalfPi = 1.5707963267948966;     // the schema's own spelling of pi/2
constexpr double kQuarterPi = 0.7853981633974483;  // outerConeAngle's default

// KHR_lights_punctual: light.spot.schema.json, and the README's "innerConeAngle ... less
// than outerConeAngle".
void check_spot(const Object& spot) {
  const double inner = spot.number("innerConeAngle", Range{0, false, kHalfPi, true}).value_or(0);
  const double outer = spot.number("outerConeAngle", Range{0, true, kHalfPi, false}).value_or(kQuarterPi);
  if (inner >= outer)
    spot.fail_spec("innerConeAngle", fmt::format("is {} with outerConeAngle {}", inner, outer),
                   "must be less than outerConeAngle");
}

void check_light(const Object& light) {
  light.required("type");
  const std::string type = *light.string_enum("type", {"directional", "point", "spot"});
  light.number_array("color", exactly(3), unit_interval());
  light.number("intensity", at_least(0));
  light.number("range", above(0));
  if (type == "spot" && !light.has("spot"))
    light.fail_spec("spot", "is missing", "required when type is \"spot\"");
  light.object("spot", "light.spot", check_spot);
}

void check_lights(const Object& lights) {
  lights.required("lights");
  lights.named_objects("lights", "light", check_light);
}

void check_node_light(const Object& light) {
  light.required("light");
  light.index("light");
}

void check_instancing(const Object& instancing) { instancing.index_map("attributes"); }

void check_draco(const Object& draco) {
  draco.required("bufferView");
  draco.index("bufferView");
  draco.required("attributes");
  draco.index_map("attributes");
}

// EXT_meshopt_compression README, "For the extension object to be valid, the following must hold".
void check_meshopt_layout(const Object& meshopt, const std::string& mode, const std::string& filter,
                          long long stride, double count) {
  const auto stride_must = [&](bool ok, const std::string& requirement) {
    if (!ok)
      meshopt.fail_spec("byteStride", fmt::format("is {} ({} mode, {} filter)", stride, mode, filter),
                        requirement);
  };
  if (mode == "ATTRIBUTES") stride_must(stride % 4 == 0, "must be a multiple of 4 in ATTRIBUTES mode");
  if (mode == "TRIANGLES" && std::fmod(count, 3) != 0)
    meshopt.fail_spec("count", fmt::format("is {}", count), "must be a multiple of 3 in TRIANGLES mode");
  if (mode != "ATTRIBUTES") {
    stride_must(stride == 2 || stride == 4, "must be 2 or 4 in " + mode + " mode");
    if (filter != "NONE")
      meshopt.fail_spec("filter", fmt::format("is \"{}\"", filter), "must be NONE in " + mode + " mode");
  }
  if (filter == "OCTAHEDRAL")
    stride_must(stride == 4 || stride == 8, "must be 4 or 8 with the OCTAHEDRAL filter");
  if (filter == "QUATERNION") stride_must(stride == 8, "must be 8 with the QUATERNION filter");
  if (filter == "EXPONENTIAL")
    stride_must(stride % 4 == 0, "must be a multiple of 4 with the EXPONENTIAL filter");
}

void check_meshopt_view(const Object& meshopt) {
  meshopt.required("buffer");
  meshopt.index("buffer");
  meshopt.integer("byteOffset", at_least(0));
  meshopt.required("byteLength");
  meshopt.integer("byteLength", at_least(1));
  meshopt.required("byteStride");
  const double stride = *meshopt.integer("byteStride", Range{2, false, 256, false});
  meshopt.required("count");
  const double count = *meshopt.integer("count", at_least(1));
  meshopt.required("mode");
  const std::string mode = *meshopt.string_enum("mode", {"ATTRIBUTES", "TRIANGLES", "INDICES"});
  const std::string filter =
      meshopt.string_enum("filter", {"NONE", "OCTAHEDRAL", "QUATERNION", "EXPONENTIAL"}).value_or("NONE");
  check_meshopt_layout(meshopt, mode, filter, static_cast<long long>(stride), count);
}

void check_meshopt_buffer(const Object& meshopt) { meshopt.boolean("fallback"); }

void check_texture_source(const Object& source) { source.index("source"); }

void check_emissive_strength(const Object& strength) { strength.number("emissiveStrength", at_least(0)); }

void check_ior(const Object& ior) {
  // oneOf [0, 0] and [1, inf): 0 is allowed, a special value.
  const std::optional<double> value = ior.number("ior");
  if (value && *value != 0 && *value < 1) ior.fail("ior", is(ior.value().at("ior")), "must be 0 or >= 1");
}

void check_transmission(const Object& transmission) {
  transmission.number("transmissionFactor", unit_interval());
  transmission.object("transmissionTexture", "textureInfo", check_texture_info);
}

void check_specular(const Object& specular) {
  specular.number("specularFactor", unit_interval());
  specular.object("specularTexture", "textureInfo", check_texture_info);
  specular.number_array("specularColorFactor", exactly(3), at_least(0));
  specular.object("specularColorTexture", "textureInfo", check_texture_info);
}

void check_texture_transform(const Object& transform) {
  transform.number_array("offset", exactly(2));
  transform.number("rotation");
  transform.number_array("scale", exactly(2));
  transform.integer("texCoord", at_least(0));
}

}  // namespace

void check_root_extensions(const Object& gltf) {
  gltf.extension("KHR_lights_punctual", "glTF.KHR_lights_punctual", check_lights);
}

void check_node_extensions(const Object& node) {
  node.extension("KHR_lights_punctual", "node.KHR_lights_punctual", check_node_light);
  node.extension("EXT_mesh_gpu_instancing", "node.EXT_mesh_gpu_instancing", check_instancing);
}

void check_primitive_extensions(const Object& primitive) {
  primitive.extension("KHR_draco_mesh_compression", "mesh.primitive.KHR_draco_mesh_compression", check_draco);
}

void check_buffer_extensions(const Object& buffer) {
  buffer.extension("EXT_meshopt_compression", "buffer.EXT_meshopt_compression", check_meshopt_buffer);
}

void check_buffer_view_extensions(const Object& view) {
  view.extension("EXT_meshopt_compression", "bufferView.EXT_meshopt_compression", check_meshopt_view);
}

void check_material_extensions(const Object& material) {
  material.extension("KHR_materials_emissive_strength", "material.KHR_materials_emissive_strength",
                     check_emissive_strength);
  material.extension("KHR_materials_ior", "material.KHR_materials_ior", check_ior);
  material.extension("KHR_materials_transmission", "material.KHR_materials_transmission", check_transmission);
  material.extension("KHR_materials_specular", "material.KHR_materials_specular", check_specular);
}

void check_texture_info_extensions(const Object& info) {
  info.extension("KHR_texture_transform", "textureInfo.KHR_texture_transform", check_texture_transform);
}

void check_texture_extensions(const Object& texture) {
  texture.extension("EXT_texture_webp", "texture.EXT_texture_webp", check_texture_source);
  texture.extension("KHR_texture_basisu", "texture.KHR_texture_basisu", check_texture_source);
}

}  // namespace phyir::scenes::gltf::schema
