#pragma once
// A furniture catalog (PluginFurnitureCatalog.properties) turned into entries: the keys
// Sweet Home 3D's DefaultFurnitureCatalog reads, with its units converted (cm -> m, light
// and sash positions into the normalised model frame of docs/assets.md).
#include <string>
#include <string_view>
#include <vector>

#include "phyir/scenes/asset_entry.h"
#include "phyir/scenes/asset_library.h"

namespace phyir::scenes {

// The catalog file inside every .sh3f (the untranslated one; _fr, _de... are ignored).
inline constexpr const char* kFurnitureCatalogName = "PluginFurnitureCatalog.properties";

struct FurnitureCatalog {
  AssetArchive archive;  // name, id, licence (path, licence text and count left to the caller)
  std::vector<AssetEntry> entries;
};

// Throws phyir::Error naming `archive_name`, the key, its value and the line.
FurnitureCatalog read_furniture_catalog(std::string_view latin1_text, const std::string& archive_name);

}  // namespace phyir::scenes
