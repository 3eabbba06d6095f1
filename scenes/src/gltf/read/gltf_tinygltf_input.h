#pragma once
// What tinygltf 2.7 is given to read. Two of its limits refuse valid compressed files:
// - a buffer without uri: refused in a .gltf, and in a .glb filled with the BIN chunk's
//   bytes; an EXT_meshopt_compression fallback buffer may have none. Such a buffer gets a
//   one-byte data URI instead (gltf_meshopt then empties it: it is never read).
// - an index accessor without bufferView ("accessor[i] invalid bufferView"), which is how
//   a KHR_draco_mesh_compression primitive's indices look. In a file that mentions Draco,
//   every primitive's "indices" without a bufferView is hidden from tinygltf and put back
//   in the parsed model (the loader then reads Draco's faces, or the accessor's zeros and
//   sparse values like any accessor without a bufferView).
// Files with neither are given to tinygltf as they are.
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include "gltf/read/gltf_file.h"

namespace phyir::scenes::gltf {

struct HiddenIndices {
  size_t mesh = 0;
  size_t primitive = 0;
  int accessor = -1;
};

struct TinygltfInput {
  std::optional<std::string> bytes;  // replaces the file's JSON (or whole GLB); nullopt: as is
  std::vector<HiddenIndices> hidden_indices;
};

TinygltfInput prepare_tinygltf_input(const GltfFile& file, const Diagnostics& diagnostics);

// Puts back the indices prepare_tinygltf_input hid.
void restore_hidden_indices(const TinygltfInput& input, tinygltf::Model& model);

// A buffer object marked {"extensions": {"EXT_meshopt_compression": {"fallback": true}}}.
bool is_meshopt_fallback(const nlohmann::json& buffer);

}  // namespace phyir::scenes::gltf
