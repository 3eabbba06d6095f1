#pragma once
// manifest.json: the one file a user needs to load a dataset (schema: docs/dataset.md).
// It is rebuilt at the end of a run from the views' own records (views/<scene>/<v>/view.json)
// and written atomically, so it exists only when every view of the run is complete.
//
// One JSON document, not JSON Lines: a dataset (or shard) has one header (settings, shard,
// splits, scenes, conventions) that every view refers to, readers load it with any JSON
// parser in one call, and it is replaced atomically as a whole. The append-friendly log that
// JSON Lines would give is the per-view view.json files. The text puts one scene and one
// view per line, so it stays readable and diffable at 30,000 views.
//
// The text is a pure function of its content (keys sorted, numbers in nlohmann::json's
// shortest round-trip form, no timestamps, no thread counts, no absolute paths unless the
// scenes folder was given as one), so equal datasets have byte-identical manifests.
#include <filesystem>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "phyir/dataset/layout.h"
#include "phyir/dataset/shard.h"

namespace phyir::dataset {

using view::kManifestFormat;
using view::kManifestVersion;

struct Manifest {
  nlohmann::json settings;                 // DatasetSettings::to_json()
  std::string scenes_dir;                  // as given to `generate`
  Shard shard;
  std::vector<std::string> scene_names;    // every scene of the dataset, sorted
  std::vector<nlohmann::json> scenes;      // records of the scenes with views here, sorted by name
  std::vector<nlohmann::json> views;       // view records (view.json), in global view order

  int views_per_scene() const { return settings.at("views_per_scene").get<int>(); }
  size_t views_total() const { return scene_names.size() * size_t(views_per_scene()); }
};

// The record of one scene: name, file, size and sha256 of the glTF, its external buffers
// and images (dependencies, each with size and sha256), content_sha256 (SHA-256 of the
// sha256sum-style lines of the glTF and every dependency), split and views.
nlohmann::json scene_record(const std::filesystem::path& scenes_dir, const SceneFile& scene, const std::string& split,
                            int views_per_scene);

// The manifest's text (deterministic layout, see above).
std::string manifest_text(const Manifest& manifest);

// Parses and checks the structure (every view through view::parse_view_record); `source`
// names the file in error messages.
Manifest parse_manifest(const nlohmann::json& json, const std::string& source);

// Reads <dir>/manifest.json (view::read_manifest_document). Throws phyir::Error naming the
// file (and saying the run has not finished when it is missing).
Manifest read_manifest(const std::filesystem::path& dir);

// Writes <dir>/manifest.json atomically.
void write_manifest(const std::filesystem::path& dir, const Manifest& manifest);

// The manifest's entry for a view is its view.json plus "path" (scenes_dir/file) in its
// "scene" block; this removes that again (for comparing the two).
nlohmann::json view_record_without_path(nlohmann::json view);

// A dataset-wide description of every file in a view folder (render outputs, input.png,
// render.json, view.json, timing.json) and the conventions they follow.
nlohmann::json dataset_conventions();

// "settings.render.spp: 4 here, 8 there" for the first difference between two JSON values,
// or "" when they are equal.
std::string describe_difference(const nlohmann::json& here, const nlohmann::json& there, const std::string& root);

}  // namespace phyir::dataset
