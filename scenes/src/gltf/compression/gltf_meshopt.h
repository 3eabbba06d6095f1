#pragma once
// EXT_meshopt_compression: bufferViews whose bytes are stored compressed in another
// buffer. Each is decoded (meshoptimizer's attribute, triangle or index codec, then its
// filter) into a buffer of its own and the bufferView is pointed at it, so accessors read
// it like any other view. Fallback buffers, placeholders for the uncompressed data that
// often have none, are never read.
#include "gltf/read/gltf_context.h"

namespace phyir::scenes::gltf {

// A buffer marked {"extensions": {"EXT_meshopt_compression": {"fallback": true}}}.
bool is_meshopt_fallback(const tinygltf::Buffer& buffer);

// Decodes every bufferView that has the extension, even when the extension is only used
// and the fallback has data (the compressed data is preferred). Fails, naming the
// bufferView, on a malformed extension object, compressed bytes outside their buffer,
// a decoded size that disagrees with the view, and data the decoder rejects; and on any
// bufferView without the extension that points into a fallback buffer.
void decode_meshopt_views(tinygltf::Model& model, const Diagnostics& diagnostics);

}  // namespace phyir::scenes::gltf
