#include "gltf/read/gltf_preflight.h"

#include <fmt/ranges.h>
#include <nlohmann/json.hpp>

#include <optional>

#include "gltf/read/gltf_extensions.h"
#include "gltf/read/gltf_tinygltf_input.h"
#include "gltf/schema/gltf_schema.h"

namespace phyir::scenes::gltf {

namespace fs = std::filesystem;
using nlohmann::json;

namespace {

int hex_value(char c) {
  if (c >= '0' && c <= '9') return c - '0';
  if (c >= 'a' && c <= 'f') return c - 'a' + 10;
  if (c >= 'A' && c <= 'F') return c - 'A' + 10;
  return -1;
}

bool is_data_uri(const std::string& uri) { return uri.rfind("data:", 0) == 0; }

// Integers that passed the schema check are written as integers (gltf_schema_rules.cpp).
std::optional<uint64_t> unsigned_member(const json& object, const char* key) {
  const auto it = object.find(key);
  if (it == object.end() || !it->is_number_integer() || it->get<int64_t>() < 0) return std::nullopt;
  return it->get<uint64_t>();
}

std::string string_member(const json& object, const char* key) {
  const auto it = object.find(key);
  return it != object.end() && it->is_string() ? it->get<std::string>() : std::string();
}

const json& array_member(const json& object, const char* key) {
  static const json empty = json::array();
  const auto it = object.find(key);
  return it != object.end() && it->is_array() ? *it : empty;
}

json parse_json(const GltfFile& file, const Diagnostics& diagnostics) {
  try {
    return json::parse(file.json.begin(), file.json.end());
  } catch (const std::exception& e) {  // json::exception; std:: so no RTTI mismatch between builds can let one through
    // parse_error, and out_of_range for numbers beyond double such as 1e999. Drop
    // nlohmann's "[json.exception.parse_error.101] " prefix; keep line and column.
    std::string what = e.what();
    const auto bracket = what.find("] ");
    diagnostics.fail("invalid JSON: {}", bracket == std::string::npos ? what : what.substr(bracket + 2));
  }
}

// The schema check has made sure of the version's form; here its major version is read.
void check_asset_version(const json& doc, const Diagnostics& diagnostics) {
  const std::string version = string_member(doc.at("asset"), "version");
  if (version.rfind("2.", 0) != 0)
    diagnostics.fail("asset.version '{}' is not supported (glTF 2.x only)", version);
}

void check_required_extensions(const json& doc, const Diagnostics& diagnostics) {
  for (const json& name : array_member(doc, "extensionsRequired")) {
    if (!is_supported_extension(name.get<std::string>())) {
      diagnostics.fail("required extension {} is not supported (supported: {})", name.get<std::string>(),
                       fmt::join(supported_extensions(), ", "));
    }
  }
}

// Bytes a base64 data URI decodes to, or nullopt when it is not well-formed base64.
std::optional<uint64_t> data_uri_size(const std::string& uri) {
  const auto comma = uri.find(',');
  if (comma == std::string::npos || uri.rfind(";base64", comma) == std::string::npos) return std::nullopt;
  const size_t length = uri.size() - comma - 1;
  if (length % 4 != 0) return std::nullopt;
  size_t padding = 0;
  for (size_t i = uri.size(); i > comma + 1 && uri[i - 1] == '='; --i) ++padding;
  if (padding > 2) return std::nullopt;
  return length / 4 * 3 - padding;
}

// The byteLength of every buffer, each checked against the data it points to.
std::vector<uint64_t> check_buffers(const json& doc, const GltfFile& file, const Diagnostics& diagnostics) {
  std::vector<uint64_t> sizes;
  const json& buffers = array_member(doc, "buffers");
  for (size_t i = 0; i < buffers.size(); ++i) {
    const json& buffer = buffers[i];
    const auto byte_length = unsigned_member(buffer, "byteLength");
    const std::string uri = string_member(buffer, "uri");
    if (uri.empty() && is_meshopt_fallback(buffer)) {  // holds no data and is never read
      sizes.push_back(0);
      continue;
    }
    if (uri.empty()) {
      if (!file.binary || i != 0) diagnostics.fail("buffer {} has no uri", i);
      if (*byte_length > file.bin_chunk_size)
        diagnostics.fail("buffer 0 byteLength {} exceeds the GLB BIN chunk ({} bytes)", *byte_length,
                         file.bin_chunk_size);
    } else if (is_data_uri(uri)) {
      const auto size = data_uri_size(uri);
      if (!size) diagnostics.fail("buffer {} data URI is not valid base64", i);
      if (*size != *byte_length)
        diagnostics.fail("buffer {} data URI holds {} bytes but its byteLength is {}", i, *size,
                         *byte_length);
    } else {
      const fs::path path = resolve_uri(file.path.parent_path(), uri);
      std::error_code ec;
      if (!fs::is_regular_file(path, ec))
        diagnostics.fail("buffer {} uri '{}' not found (looked for {})", i, uri, path.string());
      const uint64_t size = fs::file_size(path, ec);
      if (ec || size != *byte_length)
        diagnostics.fail("buffer {} uri '{}' holds {} bytes but its byteLength is {}", i, uri, size,
                         *byte_length);
    }
    sizes.push_back(*byte_length);
  }
  return sizes;
}

void check_images(const json& doc, const GltfFile& file, const std::vector<uint64_t>& buffer_sizes,
                  const Diagnostics& diagnostics) {
  const json& images = array_member(doc, "images");
  const json& views = array_member(doc, "bufferViews");
  for (size_t i = 0; i < images.size(); ++i) {
    const json& image = images[i];
    if (image.contains("bufferView")) {
      const auto view_index = unsigned_member(image, "bufferView");
      if (!view_index || *view_index >= views.size())
        diagnostics.fail("image {} bufferView does not exist ({} bufferViews)", i, views.size());
      const json& view = views[*view_index];
      const auto buffer = view.is_object() ? unsigned_member(view, "buffer") : std::nullopt;
      const auto length = view.is_object() ? unsigned_member(view, "byteLength") : std::nullopt;
      const uint64_t offset = view.is_object() ? unsigned_member(view, "byteOffset").value_or(0) : 0;
      if (!buffer || *buffer >= buffer_sizes.size() || !length || *length == 0)
        diagnostics.fail("image {} bufferView {} has no valid buffer and byteLength", i, *view_index);
      const uint64_t size = buffer_sizes[*buffer];
      if (offset > size || *length > size - offset)
        diagnostics.fail(
            "image {} bufferView {} (byteOffset {}, byteLength {}) reads past the end of buffer {} ({} "
            "bytes)",
            i, *view_index, offset, *length, *buffer, size);
      continue;
    }
    const std::string uri = string_member(image, "uri");
    if (is_data_uri(uri)) continue;
    const fs::path path = resolve_uri(file.path.parent_path(), uri);
    std::error_code ec;
    if (!fs::is_regular_file(path, ec))
      diagnostics.fail("image {} uri '{}' not found (looked for {})", i, uri, path.string());
    // tinygltf reads image files whole; a URI naming e.g. /proc/kcore (a "regular file" of
    // 128 TiB) must not be read. 1 GiB is ten times the largest 16k PNG we know of.
    constexpr uint64_t kMaxImageFileBytes = uint64_t{1} << 30;
    const uint64_t size = fs::file_size(path, ec);
    if (ec || size > kMaxImageFileBytes)
      diagnostics.fail("image {} uri '{}' is {} bytes, more than an image file may be (1 GiB)", i, uri,
                       ec ? 0 : size);
  }
}

}  // namespace

fs::path resolve_uri(const fs::path& base_dir, const std::string& uri) {
  std::string decoded;
  for (size_t i = 0; i < uri.size(); ++i) {
    if (uri[i] == '%' && i + 2 < uri.size() && hex_value(uri[i + 1]) >= 0 && hex_value(uri[i + 2]) >= 0) {
      decoded += static_cast<char>(hex_value(uri[i + 1]) * 16 + hex_value(uri[i + 2]));
      i += 2;
    } else {
      decoded += uri[i];
    }
  }
  return base_dir / decoded;
}

void preflight_check(const GltfFile& file, const Diagnostics& diagnostics) {
  const json doc = parse_json(file, diagnostics);
  if (!doc.is_object()) diagnostics.fail("JSON root is not an object");
  check_schema(doc, diagnostics);
  check_asset_version(doc, diagnostics);
  check_required_extensions(doc, diagnostics);
  const std::vector<uint64_t> buffer_sizes = check_buffers(doc, file, diagnostics);
  check_images(doc, file, buffer_sizes, diagnostics);
}

}  // namespace phyir::scenes::gltf
