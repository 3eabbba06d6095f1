#pragma once
// glTF 2.0 loading: a .gltf (with .bin / image files beside it, or data: URIs) or a .glb
// becomes a Scene baked to world space. What is supported, and what happens to the rest,
// is listed in docs/gltf-support.md.
#include <filesystem>

#include "phyir/scenes/scene.h"

namespace phyir::scenes {

struct LoadOptions {
  // false: textures keep their name and sampler but are not decoded (faster, for tools
  // that only need geometry or counts).
  bool load_textures = true;
};

// Loads .gltf or .glb (recognised by content). Throws phyir::Error whose message starts
// with the file path and names the exact problem ("room.gltf: accessor 7 (POSITION of
// mesh 0 'wall' primitive 0) reads past the end of bufferView 2: ..."). Everything skipped
// or approximated is in Scene::warnings and logged with spdlog::warn.
Scene load_gltf(const std::filesystem::path& path, const LoadOptions& options = {});

}  // namespace phyir::scenes
