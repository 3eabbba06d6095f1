#pragma once
// The node hierarchy of the default scene, flattened to world transforms.
#include <glm/glm.hpp>

#include <vector>

#include "gltf/read/gltf_context.h"

namespace phyir::scenes::gltf {

struct NodeInstance {
  int node = -1;
  glm::dmat4 world{1.0};  // node to world, double so deep hierarchies keep precision
};

// The default scene's index: `scene` if present, else 0; -1 when the file has no scenes.
int default_scene_index(const GltfContext& ctx);

// The root nodes to draw: the default scene's nodes or, with no scenes at all, every node
// that is nobody's child (then failing if some node is reachable from none: a cycle).
std::vector<int> scene_roots(const GltfContext& ctx, int scene);

// Every node reachable from `roots`, depth first, with its world transform. Fails on a
// node reached twice (a cycle, or a node with two parents).
std::vector<NodeInstance> flatten_nodes(const GltfContext& ctx, const std::vector<int>& roots);

// The node's own transform: `matrix`, or translation * rotation * scale.
glm::dmat4 local_transform(const GltfContext& ctx, int node);

}  // namespace phyir::scenes::gltf
