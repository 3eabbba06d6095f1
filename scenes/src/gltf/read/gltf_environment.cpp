#include "gltf/read/gltf_environment.h"

#include <fmt/ranges.h>

#include "gltf/read/gltf_values.h"

namespace phyir::scenes::gltf {

namespace fs = std::filesystem;

namespace {

int hex_digit(char c) {
  if (c >= '0' && c <= '9') return c - '0';
  if (c >= 'a' && c <= 'f') return c - 'a' + 10;
  if (c >= 'A' && c <= 'F') return c - 'A' + 10;
  return -1;
}

// URIs are percent-encoded (RFC 3986); a '%' not followed by two hex digits stays as it is.
std::string percent_decode(const std::string& uri) {
  std::string out;
  for (size_t i = 0; i < uri.size(); ++i) {
    const int hi = i + 2 < uri.size() && uri[i] == '%' ? hex_digit(uri[i + 1]) : -1;
    const int lo = hi >= 0 ? hex_digit(uri[i + 2]) : -1;
    if (lo >= 0) {
      out.push_back(static_cast<char>(hi * 16 + lo));
      i += 2;
    } else {
      out.push_back(uri[i]);
    }
  }
  return out;
}

void check_members(const GltfContext& ctx, const tinygltf::Value& entry, const std::string& where) {
  for (const std::string& key : entry.Keys())
    if (key != "uri" && key != "scale")
      ctx.fail("{} has an unknown member '{}': the members are uri and scale", where, key);
}

std::string environment_uri(const GltfContext& ctx, const tinygltf::Value& entry, const std::string& where) {
  const tinygltf::Value* uri = member(entry, "uri");
  if (uri == nullptr || !uri->IsString() || uri->Get<std::string>().empty())
    ctx.fail("{} needs a 'uri': the environment map's file name relative to the glTF file", where);
  const std::string& text = uri->Get<std::string>();
  if (text.rfind("data:", 0) == 0) ctx.fail("{} uri is a data: URI: the environment must be a file", where);
  return text;
}

}  // namespace

std::optional<SceneEnvironment> read_environment(const GltfContext& ctx, int scene, const fs::path& gltf_path) {
  if (scene < 0) return std::nullopt;
  const tinygltf::Value* phyir = member(ctx.model.scenes[static_cast<size_t>(scene)].extras, "phyir");
  const tinygltf::Value* entry = phyir != nullptr ? member(*phyir, "environment") : nullptr;
  if (entry == nullptr) return std::nullopt;
  const std::string where = fmt::format("scene {} extras.phyir.environment", scene);
  if (!entry->IsObject()) ctx.fail("{} is not an object: expected {{\"uri\": \"sky.exr\", \"scale\": 1.0}}", where);
  check_members(ctx, *entry, where);
  SceneEnvironment environment;
  environment.uri = environment_uri(ctx, *entry, where);
  environment.scale = number_member(ctx, *entry, "scale", where).value_or(1.0f);
  if (environment.scale < 0.0f) ctx.fail("{} scale is {}: must be >= 0", where, environment.scale);
  environment.path = gltf_path.parent_path() / percent_decode(environment.uri);
  std::error_code ec;
  if (!fs::is_regular_file(environment.path, ec))
    ctx.fail("{} uri '{}' not found (looked for {})", where, environment.uri, environment.path.string());
  return environment;
}

}  // namespace phyir::scenes::gltf
