#pragma once
// glTF cameras placed by their node: position, forward (node -Z), up (node +Y).
#include "gltf/read/gltf_nodes.h"
#include "phyir/scenes/scene.h"

namespace phyir::scenes::gltf {

// The camera that `instance`'s node carries. Orthographic cameras are kept with
// perspective = false and a warning.
Camera make_camera(const GltfContext& ctx, const NodeInstance& instance);

}  // namespace phyir::scenes::gltf
