#pragma once
// EXT_mesh_gpu_instancing: a node that draws its mesh once per instance, each placed by
// the node's world transform times the instance's translation * rotation * scale.
#include <glm/glm.hpp>

#include <cstddef>
#include <optional>

#include "gltf/read/gltf_accessors.h"
#include "gltf/read/gltf_nodes.h"
#include "gltf/read/gltf_primitives.h"
#include "phyir/scenes/scene.h"

namespace phyir::scenes::gltf {

// The node's instancing attributes, checked: each accessor exists, they agree on their
// count. -1 for an attribute the node leaves out (identity).
struct InstanceAttributes {
  int translation = -1;
  int rotation = -1;
  int scale = -1;
  size_t count = 0;
};

// nullopt when node `node` has no EXT_mesh_gpu_instancing (or has no mesh, with a
// warning). Reads no accessor data: what baking the instances will cost is known first.
std::optional<InstanceAttributes> find_gpu_instancing(const GltfContext& ctx, int node);

// The instances' transforms, read and checked (types, finite values, non-zero rotations),
// composed with the node's world transform on demand.
class InstanceTransforms {
 public:
  InstanceTransforms(const GltfContext& ctx, const NodeInstance& node, const InstanceAttributes& attributes);

  size_t size() const { return count_; }
  // world * T * R * S of instance `i`.
  glm::dmat4 world(size_t i) const;

 private:
  glm::dmat4 world_;
  size_t count_;
  FloatElements translations_;  // empty when absent
  FloatElements rotations_;     // (x, y, z, w), non-zero
  FloatElements scales_;
};

// One mesh holding every instance of `local`, each baked as bake_to_world does (a
// mirroring instance gets its winding and tangent handedness reversed).
Mesh bake_instances(const PrimitiveData& local, const InstanceTransforms& instances);

}  // namespace phyir::scenes::gltf
