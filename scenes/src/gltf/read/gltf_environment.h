#pragma once
// The environment map a scene declares: scenes[i].extras.phyir.environment =
// {"uri": "sky.exr", "scale": 1.0} (docs/gltf-support.md#environment).
#include <filesystem>
#include <optional>

#include "gltf/read/gltf_context.h"
#include "phyir/scenes/scene.h"

namespace phyir::scenes::gltf {

// The default scene's environment, its uri resolved beside `gltf_path`; nullopt without one.
// Fails naming the scene and the property on a malformed entry (not an object, no uri, a
// data: uri, scale not a finite number >= 0, an unknown member) and when the file is missing.
std::optional<SceneEnvironment> read_environment(const GltfContext& ctx, int scene,
                                                 const std::filesystem::path& gltf_path);

}  // namespace phyir::scenes::gltf
