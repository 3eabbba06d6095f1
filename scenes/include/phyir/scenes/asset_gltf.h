#pragma once
// One furniture model (asset_model.h) as a glTF document of its own, in its normalised frame
// (bottom centre at the origin, metres, +Y up), so any glTF reader, `phyir insert` among them,
// takes a library piece as it takes any other object. Materials are mapped as the library
// gives them (asset_material.h), textures are the archive's own image bytes.
#include <filesystem>

#include "phyir/scenes/asset_entry.h"
#include "phyir/scenes/asset_model.h"
#include "phyir/scenes/gltf_writer.h"

namespace phyir::scenes {

// `stem` prefixes the texture uris ("<stem>_textures/<n>.png"). Meshes are named
// "<entry name>/<k>"; the scene's extras carry the entry's name, id, library, creator and licence.
GltfDocument asset_gltf_document(const AssetEntry& entry, const AssetModel& model, const std::string& stem);

// Writes the model as `gltf_path` (+ .bin and the textures beside it; gltf_writer.h).
void write_asset_gltf(const std::filesystem::path& gltf_path, const AssetEntry& entry, const AssetModel& model);

}  // namespace phyir::scenes
