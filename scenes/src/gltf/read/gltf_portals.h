#pragma once
// The light portals a scene declares: scenes[i].extras.phyir.portals = [{"corner": [x, y, z],
// "edge_u": [x, y, z], "edge_v": [x, y, z]}, ...] in world space, each the parallelogram
// corner + a edge_u + b edge_v (a, b in [0, 1]) with edge_u x edge_v pointing into the
// interior (docs/gltf-support.md#light-portals).
#include <vector>

#include "gltf/read/gltf_context.h"
#include "phyir/scenes/scene.h"

namespace phyir::scenes::gltf {

// The default scene's portals; none without the member. Fails naming the scene, the entry
// and the property on a malformed entry (not an array of objects, a member missing, not
// three finite numbers, an unknown member, edges of no area).
std::vector<Portal> read_portals(const GltfContext& ctx, int scene);

}  // namespace phyir::scenes::gltf
