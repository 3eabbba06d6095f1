#include "phyir/view/view_record.h"

#include <algorithm>
#include <functional>

#include "phyir/core/atomic_file.h"
#include "phyir/core/error.h"
#include "phyir/view/view_files.h"

namespace fs = std::filesystem;
using nlohmann::json;

namespace phyir::view {

namespace {

const json& require(const json& j, const char* key, const std::string& source) {
  if (!j.contains(key)) fail("{}: a view record without \"{}\"", source, key);
  return j.at(key);
}

std::optional<glm::vec3> viewpoint_position(const json& record) {
  if (!record.contains("viewpoint") || !record["viewpoint"].contains("position")) return std::nullopt;
  const json& p = record["viewpoint"]["position"];
  return glm::vec3(p.at(0).get<float>(), p.at(1).get<float>(), p.at(2).get<float>());
}

json parse_json_file(const fs::path& path) {
  json j = json::parse(read_file(path), nullptr, false);
  if (j.is_discarded()) fail("{}: not valid JSON", path.string());
  return j;
}

bool is_view_folder(const fs::path& p) {
  return fs::is_regular_file(p / kColorFile) || fs::is_regular_file(p / kInputFile);
}

}  // namespace

ViewRecord parse_view_record(const json& record, const fs::path& root, const std::string& source) {
  if (!record.is_object()) fail("{}: a view record is not an object", source);
  ViewRecord v;
  try {
    v.id = record.value("id", "");
    v.dir = root / record.value("dir", "");
    if (record.contains("scene")) v.scene = record["scene"].value("name", "");
    v.split = record.value("split", "");
    v.index = record.value("index", 0);
    v.seed = record.value("seed", uint64_t(0));
    v.camera = viewpoint_position(record);
  } catch (const json::exception& e) {
    fail("{}: malformed view record: {}", source, e.what());
  }
  v.input = InputExposure::from_json(record.value("input", json()), source);
  v.json = record;
  return v;
}

ViewRecord read_view(const fs::path& dir) {
  const fs::path path = dir / kViewRecordFile;
  if (!fs::is_regular_file(path)) {
    ViewRecord v;
    v.id = dir.filename().string();
    v.dir = dir;
    return v;
  }
  ViewRecord v = parse_view_record(parse_json_file(path), dir.parent_path(), path.string());
  v.dir = dir;  // the folder it was read from, wherever the dataset has moved
  if (v.id.empty()) v.id = dir.filename().string();
  return v;
}

json read_view_json(const fs::path& dir) { return parse_json_file(dir / kViewRecordFile); }

void write_view_record(const fs::path& dir, const json& record) {
  write_file_atomic(dir / kViewRecordFile, record.dump(2) + "\n");
}

void check_manifest_format(const json& j, const std::string& source) {
  if (!j.is_object() || j.value("format", "") != kManifestFormat)
    fail("{}: not a phyir dataset manifest (\"format\" is not \"{}\")", source, kManifestFormat);
  if (j.value("format_version", 0) != kManifestVersion)
    fail("{}: manifest format_version {} is not supported (this phyir reads {})", source,
         j.value("format_version", 0), kManifestVersion);
}

json read_manifest_document(const fs::path& root) {
  const fs::path path = root / kManifestFile;
  std::error_code ec;
  if (!fs::exists(path, ec))
    fail("{}: no {} (the run that writes this folder has not finished; run the same 'phyir dataset generate' "
         "command again to complete it)",
         root.string(), kManifestFile);
  json j = parse_json_file(path);
  check_manifest_format(j, path.string());
  return j;
}

std::vector<ViewRecord> read_manifest_views(const fs::path& root, const std::string& split) {
  const json manifest = read_manifest_document(root);
  const std::string source = (root / kManifestFile).string();
  if (!manifest.contains("views") || !manifest["views"].is_array()) fail("{}: no \"views\" array", source);
  std::vector<ViewRecord> views;
  for (const json& record : manifest["views"]) {
    if (!split.empty() && record.value("split", "") != split) continue;
    for (const char* key : {"id", "dir"}) require(record, key, source);
    views.push_back(parse_view_record(record, root, source));
  }
  if (views.empty()) fail("{}: no views in split '{}'", source, split);
  return views;
}

std::vector<ViewRecord> find_views(const fs::path& root, const std::string& split) {
  if (!fs::is_directory(root)) fail("{}: not a folder", root.string());
  if (fs::is_regular_file(root / kManifestFile)) return read_manifest_views(root, split);
  if (is_view_folder(root)) return {read_view(root)};
  std::vector<fs::path> folders;
  std::function<void(const fs::path&, int)> scan = [&](const fs::path& dir, int depth) {
    for (const auto& e : fs::directory_iterator(dir)) {
      if (!e.is_directory() || e.path().filename().string().rfind(kTemporaryPrefix, 0) == 0) continue;
      if (is_view_folder(e.path())) folders.push_back(e.path());
      else if (depth < 3) scan(e.path(), depth + 1);
    }
  };
  scan(root, 1);
  std::sort(folders.begin(), folders.end());
  if (folders.empty()) fail("{}: no view folders (folders holding {} or {})", root.string(), kColorFile, kInputFile);
  std::vector<ViewRecord> views;
  for (const fs::path& folder : folders) views.push_back(read_view(folder));
  return views;
}

}  // namespace phyir::view
