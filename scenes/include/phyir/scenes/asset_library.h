#pragma once
// The Sweet Home 3D furniture libraries (.sh3f zip archives, e.g. Debian's
// sweethome3d-furniture in /usr/share/sweethome3d/furniture): their catalogs, read fast
// (no model is opened), and the models on demand (asset_model.h). docs/assets.md has the
// conventions, the keys read and the licences.
//
//   const AssetLibrary library = AssetLibrary::open("/usr/share/sweethome3d/furniture");
//   for (const AssetEntry* lamp : library.in_category("Lights")) { ... }
//   const AssetModel model = load_model(library.at("Scopia#desk_lamp1"));
#include <cstddef>
#include <filesystem>
#include <map>
#include <string>
#include <string_view>
#include <vector>

#include "phyir/scenes/asset_entry.h"
#include "phyir/scenes/asset_model.h"

namespace phyir::scenes {

// Debian's copy of the Sweet Home 3D libraries (package sweethome3d-furniture).
inline const std::filesystem::path kDefaultAssetDir = "/usr/share/sweethome3d/furniture";

// One .sh3f archive and its catalog header.
struct AssetArchive {
  std::filesystem::path path;
  std::string name;          // catalog name=
  std::string id;            // catalog id=
  std::string licence;       // catalog license= (one line)
  std::string licence_text;  // LICENSE.TXT, empty when the archive has none
  size_t entry_count = 0;
};

// The entries of one catalog text (PluginFurnitureCatalog.properties, Latin-1), without the
// archive's files: every key read is checked (numbers, booleans, counts of the space-separated
// light and sash lists). Throws phyir::Error naming `archive_name`, the key and the value.
std::vector<AssetEntry> parse_furniture_catalog(std::string_view latin1_text, const std::string& archive_name);

class AssetLibrary {
 public:
  // A folder (every *.sh3f in it, by name) or one .sh3f file. Reads each catalog and
  // checks that every model and icon it names is in its archive; throws phyir::Error naming
  // the archive and the problem (not a zip, no PluginFurnitureCatalog.properties, a bad
  // value, a missing model file). Ids repeated across archives keep their first entry.
  static AssetLibrary open(const std::filesystem::path& dir_or_file);
  static AssetLibrary open(const std::vector<std::filesystem::path>& archives);

  const std::vector<AssetEntry>& entries() const { return entries_; }
  const std::vector<AssetArchive>& archives() const { return archives_; }
  // Entries of a category, in catalog order (exact, case-sensitive name).
  std::vector<const AssetEntry*> in_category(std::string_view category) const;
  // Category name -> number of entries.
  std::map<std::string, size_t> category_counts() const;
  // nullptr when no entry has this id.
  const AssetEntry* find(std::string_view id) const;
  // Throws phyir::Error naming the id when absent.
  const AssetEntry& at(std::string_view id) const;
  // Ids skipped because an earlier archive had them.
  const std::vector<std::string>& duplicate_ids() const { return duplicate_ids_; }

 private:
  std::vector<AssetArchive> archives_;
  std::vector<AssetEntry> entries_;
  std::vector<std::string> duplicate_ids_;
};

}  // namespace phyir::scenes
