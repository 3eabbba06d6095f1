#include "gltf/schema/gltf_schema.h"

#include <nlohmann/json.hpp>

#include <regex>

#include "gltf/schema/gltf_schema_objects.h"

namespace phyir::scenes::gltf {

namespace {

using namespace schema;

// asset.version and asset.minVersion: "<major>.<minor>", no leading zeros.
std::optional<std::pair<long, long>> parse_version(const std::string& text) {
  static const std::regex pattern(R"(^(0|[1-9][0-9]{0,8})\.(0|[1-9][0-9]{0,8})$)");
  std::smatch match;
  if (!std::regex_match(text, match, pattern)) return std::nullopt;
  return std::make_pair(std::stol(match[1]), std::stol(match[2]));
}

std::optional<std::pair<long, long>> version_member(const Object& asset, const char* key) {
  const std::optional<std::string> text = asset.string(key);
  if (!text) return std::nullopt;
  const auto version = parse_version(*text);
  if (!version) asset.fail(key, is(*text), "must be <major>.<minor> such as \"2.0\"");
  return version;
}

void check_asset(const Object& asset) {
  asset.string("copyright");
  asset.string("generator");
  asset.required("version");
  const auto version = version_member(asset, "version");
  const auto min_version = version_member(asset, "minVersion");
  if (min_version && *min_version > *version)
    asset.fail_spec("minVersion", is(asset.value().at("minVersion")),
                    "must not be greater than version " + asset.value().at("version").dump());
}

void check_extension_lists(const Object& gltf) {
  gltf.string_array("extensionsUsed");
  gltf.string_array("extensionsRequired");
  if (!gltf.has("extensionsRequired")) return;
  const nlohmann::json& required = gltf.value().at("extensionsRequired");
  for (size_t i = 0; i < required.size(); ++i)
    if (gltf.document().extensions_used.count(required[i].get<std::string>()) == 0)
      gltf.fail_spec("extensionsRequired[" + std::to_string(i) + "]", is(required[i]),
                     "must also be in extensionsUsed");
}

void check_root(const Object& gltf) {
  gltf.required("asset");
  gltf.object("asset", "asset", check_asset);
  check_extension_lists(gltf);
  gltf.index("scene");
  gltf.depends_on("scene", "scenes");
  gltf.named_objects("buffers", "buffer", check_buffer);
  gltf.named_objects("bufferViews", "bufferView", check_buffer_view);
  gltf.named_objects("accessors", "accessor", check_accessor);
  gltf.named_objects("scenes", "scene", check_scene);
  gltf.named_objects("nodes", "node", check_node);
  gltf.named_objects("meshes", "mesh", check_mesh);
  gltf.named_objects("cameras", "camera", check_camera);
  gltf.named_objects("skins", "skin", check_skin);
  gltf.named_objects("animations", "animation", check_animation);
  gltf.named_objects("materials", "material", check_material);
  gltf.named_objects("textures", "texture", check_texture);
  gltf.named_objects("samplers", "sampler", check_sampler);
  gltf.named_objects("images", "image", check_image);
  check_root_extensions(gltf);
}

// Read leniently: whether the list itself is well-formed is one of the rules checked.
std::set<std::string> declared_extensions(const nlohmann::json& root) {
  std::set<std::string> names;
  const auto used = root.find("extensionsUsed");
  if (used != root.end() && used->is_array())
    for (const nlohmann::json& name : *used)
      if (name.is_string()) names.insert(name.get<std::string>());
  return names;
}

}  // namespace

void check_schema(const nlohmann::json& root, const Diagnostics& diagnostics) {
  const Document document{diagnostics, declared_extensions(root)};
  check_root(Object(root, core("glTF"), document));
}

}  // namespace phyir::scenes::gltf
