// AssetLibrary: the catalogs of a set of .sh3f archives (no model is read here).
#include "phyir/scenes/asset_library.h"

#include <algorithm>
#include <set>

#include "assets/asset_catalog.h"
#include "assets/asset_zip.h"
#include "phyir/core/error.h"
#include "phyir/core/log.h"

namespace phyir::scenes {

namespace {

std::string as_text(const std::vector<unsigned char>& bytes) { return std::string(bytes.begin(), bytes.end()); }

std::vector<std::filesystem::path> archives_in(const std::filesystem::path& dir_or_file) {
  std::error_code ec;
  if (std::filesystem::is_regular_file(dir_or_file, ec)) return {dir_or_file};
  if (!std::filesystem::is_directory(dir_or_file, ec)) fail("{}: no such folder or .sh3f file", dir_or_file.string());
  std::vector<std::filesystem::path> archives;
  for (const auto& item : std::filesystem::directory_iterator(dir_or_file)) {
    if (item.is_regular_file() && item.path().extension() == ".sh3f") archives.push_back(item.path());
  }
  if (archives.empty()) fail("{}: no .sh3f furniture library in this folder", dir_or_file.string());
  std::sort(archives.begin(), archives.end());
  return archives;
}

std::string folder_of(const std::string& path) {
  const size_t slash = path.find_last_of('/');
  return slash == std::string::npos ? "" : path.substr(0, slash + 1);
}

// Folder -> the .txt files directly in it (models' own licence notes).
std::map<std::string, std::vector<std::string>> text_files_by_folder(const ZipArchive& zip) {
  std::map<std::string, std::vector<std::string>> result;
  for (const std::string& name : zip.names()) {
    if (name.size() > 4 && name.compare(name.size() - 4, 4, ".txt") == 0 && name.find('/') != std::string::npos) {
      result[folder_of(name)].push_back(name);
    }
  }
  return result;
}

// One archive's catalog, with the checks that need the archive: every model is there.
FurnitureCatalog read_archive(const std::filesystem::path& path) {
  const ZipArchive zip(path);
  if (!zip.contains(kFurnitureCatalogName)) {
    fail("{}: no {} in this archive: not a Sweet Home 3D furniture library", path.string(), kFurnitureCatalogName);
  }
  FurnitureCatalog catalog = read_furniture_catalog(as_text(zip.read(kFurnitureCatalogName)), path.string());
  catalog.archive.path = path;
  if (zip.contains("LICENSE.TXT")) catalog.archive.licence_text = as_text(zip.read("LICENSE.TXT"));
  const auto text_files = text_files_by_folder(zip);
  for (AssetEntry& entry : catalog.entries) {
    entry.archive = path;
    const auto notes = text_files.find(folder_of(entry.model_path));
    if (notes != text_files.end() && notes->second.size() == 1) entry.licence_file = notes->second.front();
    if (!zip.contains(entry.model_path)) {
      fail("{}: model#{}={} (entry '{}'): no such file in the archive", path.string(), entry.index,
           "/" + entry.model_path, entry.id);
    }
  }
  return catalog;
}

}  // namespace

AssetLibrary AssetLibrary::open(const std::filesystem::path& dir_or_file) { return open(archives_in(dir_or_file)); }

AssetLibrary AssetLibrary::open(const std::vector<std::filesystem::path>& archives) {
  AssetLibrary library;
  std::set<std::string> ids;
  for (const auto& path : archives) {
    FurnitureCatalog catalog = read_archive(path);
    for (AssetEntry& entry : catalog.entries) {
      if (!ids.insert(entry.id).second) {
        library.duplicate_ids_.push_back(entry.id);
        spdlog::warn("{}: entry {} has the id '{}' of an earlier entry: skipped", path.string(), entry.index, entry.id);
        continue;
      }
      library.entries_.push_back(std::move(entry));
    }
    library.archives_.push_back(std::move(catalog.archive));
  }
  return library;
}

std::vector<const AssetEntry*> AssetLibrary::in_category(std::string_view category) const {
  std::vector<const AssetEntry*> result;
  for (const AssetEntry& entry : entries_) {
    if (entry.category == category) result.push_back(&entry);
  }
  return result;
}

std::map<std::string, size_t> AssetLibrary::category_counts() const {
  std::map<std::string, size_t> counts;
  for (const AssetEntry& entry : entries_) ++counts[entry.category];
  return counts;
}

const AssetEntry* AssetLibrary::find(std::string_view id) const {
  const auto it = std::find_if(entries_.begin(), entries_.end(), [&](const AssetEntry& e) { return e.id == id; });
  return it == entries_.end() ? nullptr : &*it;
}

const AssetEntry& AssetLibrary::at(std::string_view id) const {
  if (const AssetEntry* entry = find(id)) return *entry;
  fail("no furniture with the id '{}' in the {} libraries opened (see phyir assets list)", std::string(id),
       archives_.size());
}

}  // namespace phyir::scenes
