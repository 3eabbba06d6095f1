#pragma once
// Checks made on the JSON before tinygltf reads the file: the glTF schema (gltf_schema.h),
// then precise messages where tinygltf's are vague (missing .bin, missing image file,
// unsupported required extension) and a guard on its one unchecked read (an image's
// bufferView range).
#include "gltf/read/gltf_context.h"
#include "gltf/read/gltf_file.h"

namespace phyir::scenes::gltf {

void preflight_check(const GltfFile& file, const Diagnostics& diagnostics);

// Percent-decodes a relative URI ("my%20tex.png") into a path below `base_dir`.
std::filesystem::path resolve_uri(const std::filesystem::path& base_dir, const std::string& uri);

}  // namespace phyir::scenes::gltf
