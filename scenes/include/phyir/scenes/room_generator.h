#pragma once
// Procedural indoor rooms as glTF 2.0 files: plan_room() (room_layout.h) meshed and written
// as room_<index>.gltf + room_<index>.bin + room_<index>_<texture>.png. The same
// (seed, index, preset) gives byte-identical files.
#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

#include "phyir/scenes/room_layout.h"

namespace phyir::scenes {

// What one generated file holds; `phyir scenes generate` lists these in rooms.json.
struct RoomSummary {
  std::string file;  // file name of the .gltf, relative to the output folder
  size_t meshes = 0;  // glTF meshes (one primitive and one node each)
  size_t triangles = 0;
  size_t materials = 0;
  size_t textures = 0;
  size_t cameras = 0;
  size_t emissive_meshes = 0;
  size_t candidate_viewpoints = 0;  // in the scene's extras, besides the camera
  std::vector<std::string> material_kinds;  // material_kind_name() of the kinds present
};

// Writes room <index> of the series `seed` into out_dir (created if missing).
RoomSummary generate_room(const std::filesystem::path& out_dir, int index, uint64_t seed,
                          RoomPreset preset);

}  // namespace phyir::scenes
