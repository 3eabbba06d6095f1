// TextureFiles: resolving MTL texture names inside the archive (docs/assets.md, "Textures").
#include "assets/asset_textures.h"

#include <cstring>
#include <optional>

#include "assets/asset_obj.h"
#include "assets/asset_zip.h"

namespace phyir::scenes {

namespace {

std::string last_component(const std::string& path) {
  const size_t slash = path.find_last_of("/\\");
  return slash == std::string::npos ? path : path.substr(slash + 1);
}

uint32_t big_endian32(const unsigned char* p) {
  return (uint32_t(p[0]) << 24) | (uint32_t(p[1]) << 16) | (uint32_t(p[2]) << 8) | uint32_t(p[3]);
}

}  // namespace

int TextureFiles::find(const std::string& name, const std::string& raw) {
  // Sweet Home 3D tries the argument's last word first (file names with spaces second).
  const std::string last_word = raw.substr(raw.find_last_of(" \t") == std::string::npos ? 0 : raw.find_last_of(" \t") + 1);
  std::vector<std::string> candidates;
  for (const std::string& written : {name, last_word, raw}) {
    if (!written.empty()) candidates.push_back(archive_join(folder_, written));
  }
  for (const std::string& written : {name, last_word, raw}) {
    if (!written.empty()) candidates.push_back(archive_join(folder_, last_component(written)));
  }
  for (const std::string& candidate : candidates) {
    const std::optional<std::string> stored = zip_.find_ignoring_case(candidate);
    if (!stored) continue;
    const auto known = index_of_.find(*stored);
    if (known != index_of_.end()) return known->second;
    AssetTexture texture{*stored, zip_.read(*stored), false};
    texture.has_alpha = png_has_alpha(texture.bytes);
    textures_.push_back(std::move(texture));
    return index_of_[*stored] = static_cast<int>(textures_.size()) - 1;
  }
  return -1;
}

bool png_has_alpha(const std::vector<unsigned char>& bytes) {
  static const unsigned char kSignature[8] = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1A, '\n'};
  if (bytes.size() < 33 || std::memcmp(bytes.data(), kSignature, 8) != 0) return false;
  const unsigned char colour_type = bytes[25];  // IHDR: 8 signature + 8 chunk header + 9
  if (colour_type == 4 || colour_type == 6) return true;
  for (size_t at = 8; at + 8 <= bytes.size();) {  // tRNS must come before the first IDAT
    const uint32_t length = big_endian32(&bytes[at]);
    const char* type = reinterpret_cast<const char*>(&bytes[at + 4]);
    if (std::memcmp(type, "tRNS", 4) == 0) return true;
    if (std::memcmp(type, "IDAT", 4) == 0) return false;
    if (length > bytes.size()) return false;
    at += 12 + static_cast<size_t>(length);
  }
  return false;
}

}  // namespace phyir::scenes
