#pragma once
// Reading accessors with every offset, length and index checked before memory is touched
// (glTF 2.0 section 3.6). Sparse accessors, byteStride and normalized integers supported.
#include <cstdint>
#include <string>
#include <vector>

#include "gltf_context.h"

namespace phyir::scenes::gltf {

// What a use of an accessor accepts: accessor types (TINYGLTF_TYPE_*) and whether
// normalized UNSIGNED_BYTE / UNSIGNED_SHORT may stand in for FLOAT.
struct FloatFormat {
  std::vector<int> types;
  bool normalized_integers = false;
};

struct FloatElements {
  size_t count = 0;
  int components = 0;
  std::vector<float> values;  // count * components, normalized integers mapped to [0,1]
};

// `role` names the use in messages, e.g. "POSITION of mesh 0 'Cube' primitive 0".
// Non-finite values are an error naming the accessor and the element.
FloatElements read_floats(const GltfContext& ctx, int accessor, const std::string& role,
                          const FloatFormat& format);

// A SCALAR UNSIGNED_BYTE / UNSIGNED_SHORT / UNSIGNED_INT accessor (primitive indices).
std::vector<uint32_t> read_indices(const GltfContext& ctx, int accessor, const std::string& role);

// "accessor 3 (NORMAL of mesh 0 primitive 0)", the prefix of every accessor message.
std::string accessor_label(int accessor, const std::string& role);

}  // namespace phyir::scenes::gltf
