#pragma once
// The benchmark suite: the scenes every `phyir bench` figure is measured on, scene by scene
// (docs/bench-suite.md). Small generated rooms keep earlier figures comparable; furnished
// apartments (real furniture, day and night) and a room made in Blender are what users render.
//   mini                  preset mini, seed 1, room 0: a box with a table and a panel light
//   hard                  preset hard, seed 1, room 0: glass, mirrors, sphere lights
//   apartment_day_living  preset apartment, seed 1, apartment 0 (day): its living room
//   apartment_night_living                   apartment 1 (night, lamps): its living room
//   apartment_day_bedroom                    apartment 2 (day): a bedroom
//   blender_lit_room      tests/data/gltf/blender_lit_room: Blender's export, point, spot, sun
// suite.json lists them; each entry names a glTF file (relative to suite.json) and, where the
// scene's own camera is not the view, a camera position.
#include <glm/glm.hpp>

#include <filesystem>
#include <optional>
#include <string>
#include <vector>

namespace phyir::scenes {

struct SuiteScene {
  std::string name;                   // a folder name: results go to OUT/<name>/
  std::filesystem::path scene;        // the glTF file (absolute once read)
  std::optional<glm::vec3> camera;    // world position; unset: the scene's camera
  std::string what;                   // one line for tables
};

struct SuiteSources {
  std::filesystem::path asset_dir;    // the furniture library (scenes/asset_library.h)
  std::filesystem::path blender_room; // folder holding lit_room.gltf and its files
};

// Generates every scene into out_dir (created) and writes out_dir/suite.json atomically.
// Fails with a message naming what is missing (the furniture package, the Blender room).
std::vector<SuiteScene> write_bench_suite(const std::filesystem::path& out_dir, const SuiteSources& sources);

// Reads a suite.json; every scene file must exist.
std::vector<SuiteScene> read_bench_suite(const std::filesystem::path& suite_json);

}  // namespace phyir::scenes
