#pragma once
// A .gltf or .glb file read into memory, with the JSON located. GLB is recognised by its
// magic ("glTF"), not by the extension, so a misnamed file still loads.
#include <filesystem>
#include <string>
#include <string_view>

#include "gltf/read/gltf_context.h"

namespace phyir::scenes::gltf {

struct GltfFile {
  std::filesystem::path path;
  std::string bytes;          // the whole file
  bool binary = false;        // GLB container
  std::string_view json;      // the JSON text (a view into `bytes`)
  size_t bin_chunk_size = 0;  // GLB BIN chunk length, 0 when absent
};

// Reads the file and validates the GLB header and chunk layout when it is one.
GltfFile read_gltf_file(const std::filesystem::path& path, const Diagnostics& diagnostics);

}  // namespace phyir::scenes::gltf
