#pragma once
// KHR_lights_punctual: the lights the default scene's nodes carry, placed in world space.
#include <vector>

#include "gltf/read/gltf_nodes.h"
#include "phyir/scenes/scene.h"

namespace phyir::scenes::gltf {

// One light per node of `instances` that refers to one (a light used by two nodes is two
// lights). Fails on a reference to a missing light, an unknown type, and values the
// extension forbids (negative intensity, cone angles outside [0, pi/2]).
std::vector<PunctualLight> read_lights(const GltfContext& ctx, const std::vector<NodeInstance>& instances);

}  // namespace phyir::scenes::gltf
