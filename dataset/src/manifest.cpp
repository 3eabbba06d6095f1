#include "phyir/dataset/manifest.h"

#include <algorithm>
#include <cctype>
#include <map>
#include <set>

#include <fmt/format.h>

#include "phyir/core/atomic_file.h"
#include "phyir/core/error.h"
#include "phyir/dataset/checksum.h"
#include "phyir/render/render_job.h"

namespace phyir::dataset {

namespace fs = std::filesystem;
using nlohmann::json;

namespace {

using uchar = unsigned char;

std::string percent_decode(const std::string& uri) {
  std::string out;
  for (size_t i = 0; i < uri.size(); ++i) {
    if (uri[i] == '%' && i + 2 < uri.size() && std::isxdigit(uchar(uri[i + 1])) && std::isxdigit(uchar(uri[i + 2]))) {
      out += static_cast<char>(std::stoi(uri.substr(i + 1, 2), nullptr, 16));
      i += 2;
    } else {
      out += uri[i];
    }
  }
  return out;
}

// The JSON chunk of a .gltf (the whole file) or a .glb (its first chunk).
json gltf_json(const fs::path& path, const std::string& bytes) {
  if (bytes.size() >= 20 && bytes.compare(0, 4, "glTF") == 0) {
    const auto u32 = [&](size_t at) {
      return uint32_t(uchar(bytes[at])) | uint32_t(uchar(bytes[at + 1])) << 8 | uint32_t(uchar(bytes[at + 2])) << 16 |
             uint32_t(uchar(bytes[at + 3])) << 24;
    };
    const uint32_t length = u32(12);
    if (20 + size_t(length) > bytes.size()) fail("{}: truncated GLB JSON chunk", path.string());
    return json::parse(bytes.substr(20, length), nullptr, false);
  }
  return json::parse(bytes, nullptr, false);
}

// The external files a glTF names: buffers, images and the default scene's environment map
// (extras.phyir.environment.uri), percent-decoded; data: URIs are inside the file.
std::set<std::string> external_uris(const json& gltf) {
  std::set<std::string> uris;
  const auto add = [&](const json& item) {
    if (!item.is_object() || !item.contains("uri") || !item["uri"].is_string()) return;
    const std::string uri = item["uri"].get<std::string>();
    if (uri.rfind("data:", 0) != 0) uris.insert(percent_decode(uri));
  };
  for (const char* key : {"buffers", "images"}) {
    if (!gltf.contains(key) || !gltf[key].is_array()) continue;
    for (const json& item : gltf[key]) add(item);
  }
  const json scenes = gltf.value("scenes", json::array());
  const json scene_index = gltf.value("scene", json(0));
  if (scenes.is_array() && scene_index.is_number_unsigned() && scene_index.get<size_t>() < scenes.size()) {
    const json* node = &scenes[scene_index.get<size_t>()];
    for (const char* key : {"extras", "phyir", "environment"}) {
      node = node->is_object() && node->contains(key) ? &(*node)[key] : nullptr;
      if (node == nullptr) break;
    }
    if (node != nullptr) add(*node);
  }
  return uris;
}

// The default scene's "extras" object, or an empty object.
json default_scene_extras(const json& gltf) {
  const json scenes = gltf.value("scenes", json::array());
  const json scene_index = gltf.value("scene", json(0));
  if (!scenes.is_array() || !scene_index.is_number_unsigned() || scene_index.get<size_t>() >= scenes.size())
    return json::object();
  const json& scene = scenes[scene_index.get<size_t>()];
  return scene.is_object() && scene.contains("extras") && scene["extras"].is_object() ? scene["extras"] : json::object();
}

// Every credited model of the manifest's scenes once, sorted, without public-domain ones
// (CC-0 asks for no credit): the attribution the dataset's views need.
json credits(const std::vector<json>& scenes) {
  std::map<std::string, json> by_key;
  for (const json& s : scenes) {
    if (!s.contains("attribution")) continue;
    for (const json& a : s["attribution"]) {
      const std::string licence = a.value("licence", "");
      if (licence.find("Public domain") != std::string::npos || licence.find("CC-0") != std::string::npos ||
          licence.find("CC0") != std::string::npos)
        continue;
      by_key.emplace(a.value("library", "") + "|" + a.value("id", ""), a);
    }
  }
  json out = json::array();
  for (auto& [key, a] : by_key) out.push_back(a);
  return out;
}

json file_entry(const fs::path& path, const std::string& name) {
  std::error_code ec;
  const auto size = fs::file_size(path, ec);
  if (ec) fail("{}: cannot read: {}", path.string(), ec.message());
  return {{"file", name}, {"size", size}, {"sha256", sha256_file(path)}};
}

// "  " before every line after the first, so a pretty-printed value nests in the text.
std::string indented(const json& value) {
  std::string text = value.dump(2);
  std::string out;
  for (char c : text) {
    out += c;
    if (c == '\n') out += "  ";
  }
  return out;
}

std::string one_per_line(const std::vector<json>& records) {
  if (records.empty()) return "[]";
  std::string out = "[\n";
  for (size_t i = 0; i < records.size(); ++i) {
    out += "    " + records[i].dump();
    out += i + 1 < records.size() ? ",\n" : "\n";
  }
  return out + "  ]";
}

const json& require(const json& object, const char* key, const std::string& source) {
  if (!object.is_object() || !object.contains(key)) fail("{}: missing \"{}\"", source, key);
  return object.at(key);
}

}  // namespace

json scene_record(const fs::path& scenes_dir, const SceneFile& scene, const std::string& split, int views_per_scene) {
  const fs::path path = scenes_dir / scene.file;
  const std::string bytes = read_file(path);
  json record = {{"name", scene.name}, {"file", scene.file}, {"size", bytes.size()}, {"sha256", sha256_hex(bytes)},
                 {"split", split},     {"views", views_per_scene}};
  // External buffers, images and environment: the files the render read besides the glTF itself.
  const json gltf = gltf_json(path, bytes);
  if (gltf.is_discarded() || !gltf.is_object()) fail("{}: not glTF JSON", path.string());
  const std::set<std::string> uris = external_uris(gltf);
  json dependencies = json::array();
  std::string content = record["sha256"].get<std::string>() + "  " + scene.file + "\n";
  for (const std::string& uri : uris) {
    json entry = file_entry(path.parent_path() / uri, uri);
    content += entry["sha256"].get<std::string>() + "  " + uri + "\n";
    dependencies.push_back(std::move(entry));
  }
  record["dependencies"] = dependencies;
  record["content_sha256"] = sha256_hex(content);
  // The third-party models the scene holds (extras.attribution, written by the apartment
  // generator): what a view's publication must credit.
  const json scene_extras = default_scene_extras(gltf);
  if (scene_extras.contains("attribution") && scene_extras["attribution"].is_array())
    record["attribution"] = scene_extras["attribution"];
  return record;
}

json dataset_conventions() {
  json c = render::output_conventions();
  c["input_png"] =
      "the network's input: color.exr times 2^exposure_stops (the view's input.exposure_stops), then OpenColorIO's "
      "sRGB display with the recorded view (Standard: clip to [0,1] and the sRGB curve), 8 bits";
  c["color_png"] = "the render's own preview: color.exr at settings.render.preview_exposure_stops, Standard view";
  c["render_json"] = "phyir render's record of the view without wall-clock fields (those are in timing.json); "
                     "scene.path is relative to the manifest's scenes_dir";
  c["view_json"] = "the view's manifest entry (without scene.path), written before the folder is renamed into place";
  c["timing_json"] = "wall-clock seconds and thread counts of the view; the one file that differs between runs, "
                     "so it is not listed or checksummed";
  c["files"] = "paths relative to the view's dir; size in bytes; sha256 of the bytes; images with width, height "
               "and channels as OpenImageIO reads them";
  c["split"] = "by scene: every view of a scene is in its scene's split";
  return c;
}

std::string manifest_text(const Manifest& m) {
  std::map<std::string, size_t> per_split = {{"train", 0}, {"val", 0}, {"test", 0}};
  size_t files = 0, bytes = 0;
  for (const json& v : m.views) {
    per_split[v.at("split").get<std::string>()]++;
    for (const json& f : v.at("files")) {
      ++files;
      bytes += f.at("size").get<size_t>();
    }
  }
  json splits = {{"train", json::array()}, {"val", json::array()}, {"test", json::array()}};
  // Splits of every scene of the dataset (a shard's too): they follow from names and settings.
  std::map<std::string, std::string> split_of;
  for (const json& s : m.scenes) split_of[s.at("name").get<std::string>()] = s.at("split").get<std::string>();
  const json counts = {{"scenes", m.scene_names.size()},
                       {"scenes_in_manifest", m.scenes.size()},
                       {"views_total", m.views_total()},
                       {"views", m.views.size()},
                       {"views_per_split", per_split},
                       {"files", files},
                       {"bytes", bytes}};
  std::vector<json> views = m.views;
  for (json& v : views) {
    json& scene = v.at("scene");
    scene["path"] = (fs::path(m.scenes_dir) / scene.at("file").get<std::string>()).generic_string();
  }
  std::string text = "{\n";
  const auto field = [&](const char* key, const std::string& value, bool last = false) {
    text += fmt::format("  \"{}\": {}{}\n", key, value, last ? "" : ",");
  };
  field("format", json(kManifestFormat).dump());
  field("format_version", json(kManifestVersion).dump());
  field("generator", json(std::string("phyir ") + PHYIR_VERSION).dump());
  field("shard", json{{"index", m.shard.index}, {"count", m.shard.count}}.dump());
  field("counts", counts.dump());
  field("settings", indented(m.settings));
  field("scenes_dir", json(m.scenes_dir).dump());
  field("scene_names", json(m.scene_names).dump());
  field("conventions", indented(dataset_conventions()));
  field("scenes", one_per_line(m.scenes));
  const json credited = credits(m.scenes);
  if (!credited.empty()) field("attribution", one_per_line(std::vector<json>(credited.begin(), credited.end())));
  field("views", one_per_line(views), true);
  return text + "}\n";
}

Manifest parse_manifest(const json& j, const std::string& source) {
  view::check_manifest_format(j, source);
  Manifest m;
  try {
    m.settings = require(j, "settings", source);
    m.scenes_dir = require(j, "scenes_dir", source).get<std::string>();
    const json& shard = require(j, "shard", source);
    m.shard = {shard.at("index").get<int>(), shard.at("count").get<int>()};
    m.scene_names = require(j, "scene_names", source).get<std::vector<std::string>>();
    for (const json& s : require(j, "scenes", source)) m.scenes.push_back(s);
    for (const json& v : require(j, "views", source)) {
      for (const char* key : {"id", "scene", "index", "split", "dir", "files", "seed"}) require(v, key, source);
      view::parse_view_record(v, "", source);
      m.views.push_back(view_record_without_path(v));
    }
    m.views_per_scene();
  } catch (const nlohmann::json::exception& e) {
    fail("{}: malformed manifest: {}", source, e.what());
  }
  return m;
}

Manifest read_manifest(const fs::path& dir) {
  return parse_manifest(view::read_manifest_document(dir), (dir / kManifestFile).string());
}

void write_manifest(const fs::path& dir, const Manifest& manifest) {
  write_file_atomic(dir / kManifestFile, manifest_text(manifest));
  sync_folder(dir);
}

json view_record_without_path(json view) {
  if (view.contains("scene") && view["scene"].is_object()) view["scene"].erase("path");
  return view;
}

std::string describe_difference(const json& here, const json& there, const std::string& root) {
  const json patch = json::diff(here, there);
  if (patch.empty()) return "";
  const json& op = patch.front();
  const json::json_pointer pointer(op.at("path").get<std::string>());
  std::string name = root;
  for (char c : pointer.to_string()) name += c == '/' ? '.' : c;
  const auto value_at = [&](const json& j) {
    return j.contains(pointer) ? j.at(pointer).dump() : std::string("(absent)");
  };
  return fmt::format("{}: {} vs {}", name, value_at(here), value_at(there));
}

}  // namespace phyir::dataset
