#include "gltf/read/gltf_tinygltf_input.h"

#include <cstdint>
#include <cstring>

namespace phyir::scenes::gltf {

namespace {

using nlohmann::json;

// The smallest data tinygltf accepts for a buffer: it refuses an empty data URI.
constexpr char kPlaceholderUri[] = "data:application/octet-stream;base64,AA==";
constexpr uint64_t kPlaceholderBytes = 1;

const json* find_member(const json& object, const char* key) {
  if (!object.is_object()) return nullptr;
  const auto it = object.find(key);
  return it != object.end() ? &*it : nullptr;
}

bool has_uri(const json& buffer) {
  const json* uri = find_member(buffer, "uri");
  return uri != nullptr && uri->is_string() && !uri->get<std::string>().empty();
}

// Gives each fallback buffer without a uri the placeholder; returns how many it changed.
int replace_missing_fallbacks(json& doc) {
  int replaced = 0;
  const auto buffers = doc.find("buffers");
  if (buffers == doc.end() || !buffers->is_array()) return 0;
  for (json& buffer : *buffers) {
    if (!is_meshopt_fallback(buffer) || has_uri(buffer)) continue;
    buffer["uri"] = kPlaceholderUri;
    buffer["byteLength"] = kPlaceholderBytes;
    ++replaced;
  }
  return replaced;
}

// The accessor of the primitive's "indices" when it has no bufferView, else -1.
int indices_without_view(const json& primitive, const json& accessors) {
  const json* indices = find_member(primitive, "indices");
  if (indices == nullptr || !indices->is_number_unsigned()) return -1;
  const uint64_t index = indices->get<uint64_t>();
  if (!accessors.is_array() || index >= accessors.size()) return -1;  // left to tinygltf's check
  const bool has_view = find_member(accessors[index], "bufferView") != nullptr;
  return has_view ? -1 : static_cast<int>(index);
}

std::vector<HiddenIndices> hide_indices_without_view(json& doc) {
  std::vector<HiddenIndices> hidden;
  const json* accessors = find_member(doc, "accessors");
  const auto meshes = doc.find("meshes");
  if (accessors == nullptr || meshes == doc.end() || !meshes->is_array()) return hidden;
  for (size_t m = 0; m < meshes->size(); ++m) {
    json* primitives = (*meshes)[m].is_object() && (*meshes)[m].contains("primitives")
                           ? &(*meshes)[m]["primitives"]
                           : nullptr;
    if (primitives == nullptr || !primitives->is_array()) continue;
    for (size_t p = 0; p < primitives->size(); ++p) {
      const int accessor = indices_without_view((*primitives)[p], *accessors);
      if (accessor < 0) continue;
      (*primitives)[p].erase("indices");
      hidden.push_back({m, p, accessor});
    }
  }
  return hidden;
}

void append_u32(std::string& out, uint32_t value) {
  char bytes[4];
  std::memcpy(bytes, &value, sizeof bytes);  // GLB is little-endian, as are our machines
  out.append(bytes, sizeof bytes);
}

// The GLB with its JSON chunk replaced by `json_text`; the chunks after it are kept.
std::string rebuild_glb(const GltfFile& file, std::string json_text, const Diagnostics& diagnostics) {
  constexpr uint32_t kGlbMagic = 0x46546C67;                   // "glTF"
  constexpr uint32_t kChunkJson = 0x4E4F534A;                  // "JSON"
  while (json_text.size() % 4 != 0) json_text.push_back(' ');  // chunks are 4-byte aligned
  const size_t json_end = static_cast<size_t>(file.json.data() - file.bytes.data()) + file.json.size();
  const std::string_view later_chunks = std::string_view(file.bytes).substr(json_end);
  const uint64_t total = 12 + 8 + uint64_t{json_text.size()} + later_chunks.size();
  if (total > UINT32_MAX) diagnostics.fail("GLB file is larger than 4 GiB");
  std::string glb;
  glb.reserve(total);
  append_u32(glb, kGlbMagic);
  append_u32(glb, 2);
  append_u32(glb, static_cast<uint32_t>(total));
  append_u32(glb, static_cast<uint32_t>(json_text.size()));
  append_u32(glb, kChunkJson);
  glb += json_text;
  glb.append(later_chunks.data(), later_chunks.size());
  return glb;
}

bool mentions(std::string_view json_text, const char* word) {
  return json_text.find(word) != std::string_view::npos;
}

}  // namespace

bool is_meshopt_fallback(const json& buffer) {
  const json* extensions = find_member(buffer, "extensions");
  const json* meshopt = extensions != nullptr ? find_member(*extensions, "EXT_meshopt_compression") : nullptr;
  const json* fallback = meshopt != nullptr ? find_member(*meshopt, "fallback") : nullptr;
  return fallback != nullptr && fallback->is_boolean() && fallback->get<bool>();
}

TinygltfInput prepare_tinygltf_input(const GltfFile& file, const Diagnostics& diagnostics) {
  TinygltfInput input;
  // Most files have neither: skip the second JSON parse for them.
  if (!mentions(file.json, "\"fallback\"") && !mentions(file.json, "KHR_draco_mesh_compression"))
    return input;
  json doc;
  try {
    doc = json::parse(file.json.begin(), file.json.end());
  } catch (const std::exception& e) {  // preflight_check parsed it already; kept for safety
    diagnostics.fail("invalid JSON: {}", e.what());
  }
  if (!doc.is_object()) return input;
  const int replaced = replace_missing_fallbacks(doc);
  input.hidden_indices = hide_indices_without_view(doc);
  if (replaced == 0 && input.hidden_indices.empty()) return input;
  // replace: strings were valid UTF-8 when parsed; never throw on the way out.
  std::string json_text = doc.dump(-1, ' ', false, json::error_handler_t::replace);
  input.bytes = file.binary ? rebuild_glb(file, std::move(json_text), diagnostics) : std::move(json_text);
  return input;
}

void restore_hidden_indices(const TinygltfInput& input, tinygltf::Model& model) {
  for (const HiddenIndices& h : input.hidden_indices)
    if (h.mesh < model.meshes.size() && h.primitive < model.meshes[h.mesh].primitives.size())
      model.meshes[h.mesh].primitives[h.primitive].indices = h.accessor;
}

}  // namespace phyir::scenes::gltf
