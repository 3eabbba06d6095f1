#pragma once
// Reading accessors with every offset, length and index checked before memory is touched
// (glTF 2.0 section 3.6). Sparse accessors, byteStride, normalized and quantized integers
// (KHR_mesh_quantization) supported.
#include <cstdint>
#include <string>
#include <vector>

#include "gltf/compression/gltf_quantization.h"
#include "gltf/read/gltf_context.h"

namespace phyir::scenes::gltf {

struct FloatElements {
  size_t count = 0;
  int components = 0;
  std::vector<float> values;  // count * components, integers dequantized (gltf_quantization.h)
};

// `role` names the use in messages, e.g. "POSITION of mesh 0 'Cube' primitive 0".
// Non-finite values are an error naming the accessor and the element.
FloatElements read_floats(const GltfContext& ctx, int accessor, const std::string& role,
                          const FloatFormat& format);

// For an attribute whose data is stored elsewhere (a Draco-compressed primitive): the
// accessor's type and componentType checked against `format`; its bufferView, byteOffset
// and sparse are not read (KHR_draco_mesh_compression says to ignore them).
const tinygltf::Accessor& check_float_accessor(const GltfContext& ctx, int accessor, const std::string& role,
                                               const FloatFormat& format);

// Elements tightly packed in the accessor's componentType (`packed`, whole elements) as
// floats, dequantized and checked finite like read_floats.
FloatElements floats_from_packed(const GltfContext& ctx, int accessor, const std::string& role,
                                 const std::vector<unsigned char>& packed);

// A SCALAR UNSIGNED_BYTE / UNSIGNED_SHORT / UNSIGNED_INT accessor (primitive indices).
std::vector<uint32_t> read_indices(const GltfContext& ctx, int accessor, const std::string& role);

// "accessor 3 (NORMAL of mesh 0 primitive 0)", the prefix of every accessor message.
std::string accessor_label(int accessor, const std::string& role);

struct ByteRange {
  const unsigned char* data = nullptr;
  size_t size = 0;
};

// The bytes of bufferView `view`, checked to lie inside its buffer; `who` names the user.
ByteRange view_bytes(const GltfContext& ctx, int view, const std::string& who);

}  // namespace phyir::scenes::gltf
