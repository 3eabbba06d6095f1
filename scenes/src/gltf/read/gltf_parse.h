#pragma once
// tinygltf's parse of a file that passed preflight_check. Images are not decoded here:
// their encoded bytes are kept in tinygltf::Image::image (as_is = true). Bufferviews
// compressed with EXT_meshopt_compression are decoded here (gltf_meshopt.h), so later
// stages read them like any other.
#include "gltf/read/gltf_context.h"
#include "gltf/read/gltf_file.h"

namespace phyir::scenes::gltf {

tinygltf::Model parse_gltf(const GltfFile& file, const Diagnostics& diagnostics);

}  // namespace phyir::scenes::gltf
