#pragma once
// The glTF writer's materials: pbrMetallicRoughness, normal and emissive textures, alpha
// mode, double-sidedness and the KHR_materials_* / KHR_texture_transform extensions.
#include <nlohmann/json.hpp>

#include <set>
#include <string>

#include "phyir/scenes/gltf_writer.h"

namespace phyir::scenes::gltf_write {

// The material's JSON; adds the extensions it uses to `extensions`. Fails naming the
// material on a texture index out of range or a value glTF forbids.
nlohmann::json encode_material(const GltfMaterial& m, const GltfDocument& doc, std::set<std::string>& extensions);

bool uses_textures(const GltfMaterial& m);

}  // namespace phyir::scenes::gltf_write
