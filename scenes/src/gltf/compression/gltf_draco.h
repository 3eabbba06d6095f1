#pragma once
// KHR_draco_mesh_compression: a primitive whose attributes and indices are stored as one
// Draco-compressed mesh in a bufferView, decoded with libdraco. The primitive's accessors
// still type each attribute (componentType, normalized, count); their bufferView, when
// present, is the uncompressed fallback and is not read: compressed data is preferred.
#include <map>
#include <string>
#include <vector>

#include "gltf/read/gltf_accessors.h"

namespace phyir::scenes::gltf {

struct DracoPrimitive {
  std::map<std::string, FloatElements> attributes;  // by glTF name, those the loader reads
  std::vector<uint32_t> indices;                    // three per decoded face
};

bool has_draco(const tinygltf::Primitive& primitive);

// Decodes the primitive's Draco data. Fails, naming `where` (the primitive), when the
// extension's bufferView is missing or outside its buffer, the decoder rejects the bytes,
// an attribute id is not in the decoded mesh or names no attribute of the primitive, or
// the decoded points, components or faces disagree with the accessors.
DracoPrimitive decode_draco(const GltfContext& ctx, const tinygltf::Primitive& primitive,
                            const std::string& where);

}  // namespace phyir::scenes::gltf
