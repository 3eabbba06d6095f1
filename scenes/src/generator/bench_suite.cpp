// The benchmark suite (bench_suite.h): generated, copied and listed in suite.json.
#include "phyir/scenes/bench_suite.h"

#include <cmath>
#include <fstream>
#include <nlohmann/json.hpp>

#include "phyir/core/atomic_file.h"
#include "phyir/core/error.h"
#include "phyir/core/setting_error.h"
#include "phyir/scenes/apartment_generator.h"
#include "phyir/scenes/asset_library.h"

namespace phyir::scenes {

namespace fs = std::filesystem;
using nlohmann::json;

namespace {

constexpr uint64_t kSeed = 1;

json read_json(const fs::path& path) {
  std::ifstream in(path);
  if (!in) fail("{}: cannot be read", path.string());
  try {
    return json::parse(in);
  } catch (const std::exception& e) {
    fail("{}: not valid JSON ({})", path.string(), e.what());
  }
}

// The first candidate viewpoint (extras.phyir.candidate_viewpoints) inside a room of this type
// (extras.phyir.rooms' floor rectangles [min x, min z, max x, max z]).
glm::vec3 viewpoint_in_room(const fs::path& gltf, const std::string& type) {
  const json doc = read_json(gltf);
  const json& phyir = doc.at("scenes").at(0).at("extras").at("phyir");
  for (const json& room : phyir.at("rooms")) {
    if (room.at("type") != type) continue;
    const json& f = room.at("floor");
    for (const json& p : phyir.at("candidate_viewpoints")) {
      const glm::vec3 v(p.at(0).get<float>(), p.at(1).get<float>(), p.at(2).get<float>());
      if (v.x >= f.at(0).get<float>() && v.z >= f.at(1).get<float>() && v.x <= f.at(2).get<float>() &&
          v.z <= f.at(3).get<float>())
        return v;
    }
  }
  fail("{}: no candidate viewpoint in a room of type '{}'", gltf.string(), type);
}

std::vector<SuiteScene> generated_rooms(const fs::path& out_dir) {
  std::vector<SuiteScene> suite;
  for (const auto& [name, preset, what] :
       {std::tuple{"mini", RoomPreset::Mini, "generated mini room (a table, one panel light)"},
        std::tuple{"hard", RoomPreset::Hard, "generated hard room (glass, mirrors, sphere lights)"}}) {
    generate_room(out_dir / name, 0, kSeed, preset);
    suite.push_back({name, fs::path(name) / "room_0.gltf", std::nullopt, what});
  }
  return suite;
}

std::vector<SuiteScene> apartment_rooms(const fs::path& out_dir, const fs::path& asset_dir) {
  if (!fs::exists(asset_dir))
    fail_setting("asset_dir", "{}: no furniture library: install the Debian package sweethome3d-furniture "
                 "(scripts/install_deps.sh does) or name a folder with .sh3f files", asset_dir.string());
  const AssetLibrary library = AssetLibrary::open(asset_dir);
  const fs::path dir = out_dir / "apartments";
  for (int index = 0; index < 3; ++index) generate_apartment(dir, index, kSeed, library, ApartmentOptions{});
  const fs::path bedroom_scene = fs::path("apartments") / "apartment_2.gltf";
  return {{"apartment_day_living", fs::path("apartments") / "apartment_0.gltf", std::nullopt,
           "furnished apartment by day (sky, sun through windows): living room"},
          {"apartment_night_living", fs::path("apartments") / "apartment_1.gltf", std::nullopt,
           "furnished apartment at night (lamps, glowing shades): living room"},
          {"apartment_day_bedroom", bedroom_scene, viewpoint_in_room(out_dir / bedroom_scene, "bedroom"),
           "furnished apartment by day: a bedroom"}};
}

SuiteScene blender_room(const fs::path& out_dir, const fs::path& source) {
  if (!fs::is_regular_file(source / "lit_room.gltf"))
    fail("{}: no lit_room.gltf (the Blender-exported room of tests/data/gltf/blender_lit_room)", source.string());
  const fs::path dir = out_dir / "blender_lit_room";
  fs::create_directories(dir);
  // The glTF and the files beside it (buffer, images); not the folders (its variants).
  for (const fs::directory_entry& e : fs::directory_iterator(source))
    if (e.is_regular_file()) fs::copy_file(e.path(), dir / e.path().filename(), fs::copy_options::overwrite_existing);
  return {"blender_lit_room", fs::path("blender_lit_room") / "lit_room.gltf", std::nullopt,
          "room exported by Blender (point, spot, sun, textures)"};
}

}  // namespace

std::vector<SuiteScene> write_bench_suite(const fs::path& out_dir, const SuiteSources& sources) {
  fs::create_directories(out_dir);
  std::vector<SuiteScene> suite = generated_rooms(out_dir);
  for (SuiteScene& s : apartment_rooms(out_dir, sources.asset_dir)) suite.push_back(std::move(s));
  suite.push_back(blender_room(out_dir, sources.blender_room));
  json list = json::array();
  for (const SuiteScene& s : suite) {
    json entry = {{"name", s.name}, {"scene", s.scene.generic_string()}, {"what", s.what}};
    auto mm = [](float v) { return std::round(double(v) * 1000.0) / 1000.0; };  // as the viewpoints' grid
    if (s.camera) entry["camera"] = {mm(s.camera->x), mm(s.camera->y), mm(s.camera->z)};
    list.push_back(entry);
  }
  write_file_atomic(out_dir / "suite.json", json{{"seed", kSeed}, {"scenes", list}}.dump(2) + "\n");
  return read_bench_suite(out_dir / "suite.json");
}

std::vector<SuiteScene> read_bench_suite(const fs::path& suite_json) {
  const json doc = read_json(suite_json);
  if (!doc.contains("scenes") || !doc["scenes"].is_array() || doc["scenes"].empty())
    fail("{}: no \"scenes\" list", suite_json.string());
  std::vector<SuiteScene> suite;
  for (const json& e : doc["scenes"]) {
    SuiteScene s;
    try {
      s.name = e.at("name").get<std::string>();
      s.scene = suite_json.parent_path() / e.at("scene").get<std::string>();
      s.what = e.value("what", "");
      if (e.contains("camera")) s.camera = glm::vec3(e["camera"].at(0).get<float>(), e["camera"].at(1).get<float>(),
                                                     e["camera"].at(2).get<float>());
    } catch (const std::exception& ex) {
      fail("{}: a scene entry is malformed ({})", suite_json.string(), ex.what());
    }
    if (s.name.empty() || s.name.find('/') != std::string::npos)
      fail("{}: scene name '{}' must be a plain folder name", suite_json.string(), s.name);
    if (!fs::is_regular_file(s.scene)) fail("{}: scene {} does not exist", suite_json.string(), s.scene.string());
    suite.push_back(std::move(s));
  }
  return suite;
}

}  // namespace phyir::scenes
