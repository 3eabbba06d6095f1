#pragma once
// The glTF writer's textures: images (one per uri), samplers (one per distinct wrap mode,
// in order of first use) and the textures pairing them.
#include <nlohmann/json.hpp>

#include <vector>

#include "phyir/scenes/gltf_writer.h"

namespace phyir::scenes::gltf_write {

struct EncodedTextures {
  nlohmann::json images = nlohmann::json::array();
  nlohmann::json samplers = nlohmann::json::array();
  nlohmann::json textures = nlohmann::json::array();
  std::vector<GltfSideFile> side_files;  // the images with a source, each uri once
};

// Fails naming the texture on a bad uri, a missing source file, bytes that are neither PNG
// nor JPEG, or two different sources under one uri.
EncodedTextures encode_textures(const std::vector<GltfTexture>& textures);

}  // namespace phyir::scenes::gltf_write
