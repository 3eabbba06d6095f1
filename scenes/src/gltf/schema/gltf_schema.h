#pragma once
// The glTF 2.0 JSON schema, and those of the extensions the loader reads, checked on the
// JSON before tinygltf sees it: tinygltf tolerates what the schema forbids (a negative
// byteOffset reads as 0, an unknown mode as triangles). The first violation ends the load
// with a phyir::Error naming the object, the value and the rule:
//   "room.gltf: accessors[3].byteOffset is -4: must be >= 0 (glTF 2.0 schema, accessor.byteOffset)".
// A few rules come from the specs' prose, named "(glTF 2.0 spec, ...)". docs/robustness.md
// ("Schema validation") lists them and where the Khronos validator disagrees.
#include <nlohmann/json_fwd.hpp>

#include "gltf/read/gltf_context.h"

namespace phyir::scenes::gltf {

// `root` is the parsed JSON root, already known to be an object.
void check_schema(const nlohmann::json& root, const Diagnostics& diagnostics);

}  // namespace phyir::scenes::gltf
