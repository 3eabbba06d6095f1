#pragma once
// A view's record: view.json in its folder, the same object as its entry in the dataset's
// manifest.json (docs/dataset.md "view.json"). The typed fields are what readers use; `json`
// keeps the whole record for writers and checks (checksums, render statistics).
#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include <glm/glm.hpp>
#include <nlohmann/json.hpp>

#include "phyir/view/input_exposure.h"

namespace phyir::view {

inline constexpr const char* kManifestFile = "manifest.json";
inline constexpr const char* kManifestFormat = "phyir-dataset";
inline constexpr int kManifestVersion = 1;

struct ViewRecord {
  std::string id;                     // "room_0/v003" (a folder without view.json: its name)
  std::string scene;                  // the scene's name
  std::string split;                  // train, val or test ("" outside a dataset)
  std::filesystem::path dir;          // the view folder
  int index = 0;                      // the view's index within its scene
  uint64_t seed = 0;                  // its render seed
  std::optional<glm::vec3> camera;    // the panorama's centre (viewpoint.position), metres
  InputExposure input;                // input.png's exposure
  nlohmann::json json;                // the whole record; null for a folder without view.json
};

// A record (a manifest entry or view.json) of a view whose folder is root / record.dir.
// Every field is optional here (a hand-made view.json may hold only "input"); mistyped
// fields: phyir::Error naming `source`. Manifests require id and dir (read_manifest_views).
ViewRecord parse_view_record(const nlohmann::json& record, const std::filesystem::path& root,
                             const std::string& source);

// The view in `dir`: its view.json when present, else (a `phyir render` or hand-made folder)
// a record of the folder alone (id = folder name, exposure not recorded). A view.json that
// is not valid JSON or is malformed: phyir::Error naming it.
ViewRecord read_view(const std::filesystem::path& dir);

// dir/view.json as written (for writers that compare or copy records). Missing or not valid
// JSON: phyir::Error naming it.
nlohmann::json read_view_json(const std::filesystem::path& dir);

// Writes dir/view.json atomically.
void write_view_record(const std::filesystem::path& dir, const nlohmann::json& record);

// phyir::Error naming `source` unless `manifest` is a phyir dataset manifest of this version.
void check_manifest_format(const nlohmann::json& manifest, const std::string& source);

// <root>/manifest.json, checked to be a phyir dataset manifest of this version. Missing: an
// error saying the run has not finished; invalid: an error naming the file.
nlohmann::json read_manifest_document(const std::filesystem::path& root);

// The views of the dataset at `root` in manifest order, those of `split` only unless empty.
// No view in the split: phyir::Error naming the manifest and the split.
std::vector<ViewRecord> read_manifest_views(const std::filesystem::path& root, const std::string& split = "");

// The views under `root`: with root/manifest.json, read_manifest_views; without, every folder
// (root itself, or up to three levels down, interrupted writes .tmp-* skipped) that holds
// color.exr or input.png, sorted by path, each read with read_view.
std::vector<ViewRecord> find_views(const std::filesystem::path& root, const std::string& split = "");

}  // namespace phyir::view
