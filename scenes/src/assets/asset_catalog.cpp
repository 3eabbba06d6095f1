// read_furniture_catalog: PluginFurnitureCatalog.properties -> AssetEntry, with the
// semantics of Sweet Home 3D's DefaultFurnitureCatalog (docs/assets.md, "Catalog keys").
#include "assets/asset_catalog.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <regex>

#include "assets/asset_catalog_keys.h"
#include "assets/asset_properties.h"
#include "phyir/core/error.h"

namespace phyir::scenes {

namespace {

constexpr float kCentimetre = 0.01f;
constexpr float kDegree = 3.14159265358979323846f / 180.0f;
// Below this elevation an opening without "door" or "window" in its name is a door:
// thresholds and sliding tracks are a few cm at most.
constexpr float kDoorMaxElevationM = 0.05f;

std::string lower(std::string text) {
  std::transform(text.begin(), text.end(), text.begin(), [](unsigned char c) { return std::tolower(c); });
  return text;
}

std::vector<std::string> split_tags(const std::string& text) {
  std::vector<std::string> tags;
  static const std::regex separator("\\s*,\\s*");
  for (std::sregex_token_iterator it(text.begin(), text.end(), separator, -1), end; it != end; ++it) {
    std::string tag = *it;
    tag.erase(0, tag.find_first_not_of(" \t"));
    tag.erase(tag.find_last_not_of(" \t") + 1);
    if (!tag.empty()) tags.push_back(tag);
  }
  return tags;
}

// Catalog paths start with '/' (relative to the archive's root).
std::string archive_path(const CatalogKeys& keys, const std::string& prefix, int index) {
  std::string path = keys.required_text(prefix, index);
  if (path.find("!/") != std::string::npos || path.find("://") != std::string::npos) {
    keys.fail_value(prefix, index, "is a URL or a path inside a nested archive, which are not supported");
  }
  path.erase(0, path.find_first_not_of('/'));
  return path;
}

glm::mat3 model_rotation(const CatalogKeys& keys, int index) {
  if (!keys.find("modelRotation", index)) return glm::mat3(1.0f);
  const std::vector<float> m = keys.numbers("modelRotation", index, 9);
  glm::mat3 rotation;  // glm is column-major: rotation[column][row]
  for (int row = 0; row < 3; ++row) {
    for (int column = 0; column < 3; ++column) rotation[column][row] = m[static_cast<size_t>(row * 3 + column)];
  }
  if (std::abs(glm::determinant(rotation)) < 1e-6f) keys.fail_value("modelRotation", index, "is a singular matrix");
  return rotation;
}

// Catalog cm within the piece: x from the left, y from the front in plan (Sweet Home 3D
// puts a source at depth/2 - y in its 3D z), z from the bottom.
std::vector<AssetLightSource> light_sources(const CatalogKeys& keys, int index, glm::vec3 size_cm) {
  if (!keys.find("lightSourceX", index)) return {};
  const std::vector<float> x = keys.numbers("lightSourceX", index);
  const int count = static_cast<int>(x.size());
  const std::vector<float> y = keys.numbers("lightSourceY", index, count);
  const std::vector<float> z = keys.numbers("lightSourceZ", index, count);
  const std::vector<unsigned> colour = keys.colours("lightSourceColor", index, count);
  std::vector<float> diameter;
  if (keys.find("lightSourceDiameter", index)) diameter = keys.numbers("lightSourceDiameter", index, count);
  std::vector<AssetLightSource> sources(x.size());
  for (size_t i = 0; i < sources.size(); ++i) {
    sources[i].relative_position = {x[i] / size_cm.x, z[i] / size_cm.y, 1.0f - y[i] / size_cm.z};
    sources[i].colour = glm::vec3((colour[i] >> 16) & 0xFF, (colour[i] >> 8) & 0xFF, colour[i] & 0xFF) / 255.0f;
    if (!diameter.empty()) sources[i].diameter_m = diameter[i] * kCentimetre;
  }
  return sources;
}

std::vector<AssetSash> sashes(const CatalogKeys& keys, int index) {
  if (!keys.find("doorOrWindowSashXAxis", index)) return {};
  const std::vector<float> x = keys.numbers("doorOrWindowSashXAxis", index);
  const int count = static_cast<int>(x.size());
  const std::vector<float> y = keys.numbers("doorOrWindowSashYAxis", index, count);
  const std::vector<float> width = keys.numbers("doorOrWindowSashWidth", index, count);
  const std::vector<float> start = keys.numbers("doorOrWindowSashStartAngle", index, count);
  const std::vector<float> end = keys.numbers("doorOrWindowSashEndAngle", index, count);
  std::vector<AssetSash> result(x.size());
  for (size_t i = 0; i < result.size(); ++i) {
    result[i] = {x[i] * kCentimetre, y[i] * kCentimetre, width[i] * kCentimetre, start[i] * kDegree, end[i] * kDegree};
  }
  return result;
}

OpeningKind opening_kind(const AssetEntry& entry) {
  const std::string name = lower(entry.name);
  if (name.find("window") != std::string::npos) return OpeningKind::Window;
  if (name.find("door") != std::string::npos) return OpeningKind::Door;
  return entry.elevation_m < kDoorMaxElevationM ? OpeningKind::Door : OpeningKind::Window;
}

AssetOpening opening(const CatalogKeys& keys, int index, const AssetEntry& entry) {
  AssetOpening result;
  result.kind = opening_kind(entry);
  result.wall_thickness_m = keys.number("doorOrWindowWallThickness", index).value_or(entry.size_m.z / kCentimetre) * kCentimetre;
  result.wall_distance_m = keys.number("doorOrWindowWallDistance", index).value_or(0.0f) * kCentimetre;
  result.cut_out_shape = keys.text("doorOrWindowCutOutShape", index).value_or("");
  result.wall_cut_out_on_both_sides = keys.boolean("doorOrWindowWallCutOutOnBothSides", index).value_or(true);
  result.sashes = sashes(keys, index);
  return result;
}

void read_description(const CatalogKeys& keys, int index, AssetEntry& entry) {
  entry.index = index;
  entry.name = keys.required_text("name", index);
  entry.id = keys.text("id", index).value_or("");
  entry.category = keys.required_text("category", index);
  entry.creator = keys.text("creator", index).value_or("");
  entry.tags = split_tags(keys.text("tags", index).value_or(""));
  entry.description = keys.text("description", index).value_or("");
  entry.creation_date = keys.text("creationDate", index).value_or("");
  entry.model_path = archive_path(keys, "model", index);
  entry.icon_path = keys.find("icon", index) ? archive_path(keys, "icon", index) : "";
  entry.multi_part_model = keys.boolean("multiPartModel", index).value_or(false);
}

void read_geometry(const CatalogKeys& keys, int index, AssetEntry& entry) {
  const glm::vec3 size_cm(keys.required_length("width", index), keys.required_length("height", index),
                          keys.required_length("depth", index));
  entry.size_m = size_cm * kCentimetre;
  entry.elevation_m = keys.number("elevation", index).value_or(0.0f) * kCentimetre;
  entry.drop_on_top_elevation = keys.number("dropOnTopElevation", index).value_or(size_cm.y) / size_cm.y;
  entry.model_rotation = model_rotation(keys, index);
  entry.movable = keys.boolean("movable", index).value_or(true);
  entry.resizable = keys.boolean("resizable", index).value_or(true);
  entry.staircase_cut_out_shape = keys.text("staircaseCutOutShape", index).value_or("");
  entry.is_door_or_window = keys.boolean("doorOrWindow", index).value_or(false);
  // Sweet Home 3D reads light sources only for pieces that are not doors or windows.
  if (entry.is_door_or_window) {
    entry.opening = opening(keys, index, entry);
  } else {
    entry.light_sources = light_sources(keys, index, size_cm);
  }
}

}  // namespace

FurnitureCatalog read_furniture_catalog(std::string_view latin1_text, const std::string& archive_name) {
  const auto properties = read_java_properties(latin1_text, archive_name + ": " + kFurnitureCatalogName);
  const CatalogKeys keys(properties, archive_name);
  FurnitureCatalog catalog;
  catalog.archive.name = keys.text("name", 0).value_or(archive_name);
  catalog.archive.id = keys.text("id", 0).value_or("");
  catalog.archive.licence = keys.text("license", 0).value_or("");
  for (const int index : keys.entry_indices()) {
    AssetEntry entry;
    entry.library = catalog.archive.name;
    entry.archive = archive_name;
    entry.licence = catalog.archive.licence;
    read_description(keys, index, entry);
    read_geometry(keys, index, entry);
    if (entry.id.empty()) entry.id = catalog.archive.name + "#" + std::to_string(index);
    catalog.entries.push_back(std::move(entry));
  }
  if (catalog.entries.empty()) fail("{}: {} has no furniture (no name#N keys)", archive_name, kFurnitureCatalogName);
  catalog.archive.entry_count = catalog.entries.size();
  return catalog;
}

std::vector<AssetEntry> parse_furniture_catalog(std::string_view latin1_text, const std::string& archive_name) {
  return read_furniture_catalog(latin1_text, archive_name).entries;
}

}  // namespace phyir::scenes
