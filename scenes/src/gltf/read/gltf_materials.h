#pragma once
// glTF materials to Scene materials: pbrMetallicRoughness, normal and emissive maps,
// KHR_materials_emissive_strength / _transmission / _ior and KHR_texture_transform.
#include <vector>

#include "gltf/read/gltf_context.h"
#include "gltf/read/gltf_textures.h"
#include "phyir/scenes/scene.h"

namespace phyir::scenes::gltf {

// One Scene material per glTF material, in file order; textures are created in `textures`.
std::vector<Material> convert_materials(const GltfContext& ctx, TextureTable& textures);

// What a primitive without a material gets (glTF 2.0 3.9.6): white, metallic 1, roughness 1.
Material default_material();

}  // namespace phyir::scenes::gltf
