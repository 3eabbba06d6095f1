#include "phyir/render/guiding/spatial_tree.h"

#include <algorithm>

namespace phyir::render::guiding {

SpatialTree::SpatialTree(const glm::vec3& min, const glm::vec3& max) : nodes_(1), leaf_node_{0} {
  const glm::vec3 extent = glm::max(max - min, glm::vec3(0.0f));
  // A degenerate or empty box (no geometry) still gets a cell of 1 m.
  const float side = std::max({extent.x, extent.y, extent.z, 0.0f});
  size_ = (side > 0.0f ? side : 1.0f) * 1.01f;
  const glm::vec3 centre = side > 0.0f ? 0.5f * (min + max) : glm::vec3(0.0f);
  min_ = centre - glm::vec3(0.5f * size_);
}

uint32_t SpatialTree::slot_at(const glm::vec3& p) const {
  // The point in the cube's unit coordinates; each level doubles the split axis.
  glm::vec3 q = glm::clamp((p - min_) / size_, 0.0f, 1.0f);
  if (!(q.x == q.x && q.y == q.y && q.z == q.z)) q = glm::vec3(0.5f);  // a NaN point: the middle
  uint32_t node = 0;
  while (nodes_[node].child[0] != 0) {
    const int axis = nodes_[node].depth % 3;
    const int upper = q[axis] >= 0.5f ? 1 : 0;
    q[axis] = 2.0f * q[axis] - float(upper);
    node = nodes_[node].child[upper];
  }
  return nodes_[node].slot;
}

uint32_t SpatialTree::split(uint32_t slot, int max_depth) {
  const uint32_t leaf = leaf_node_[slot];
  if (nodes_[leaf].depth >= max_depth) return UINT32_MAX;
  const uint32_t new_slot = uint32_t(leaf_node_.size());
  const uint32_t lower = uint32_t(nodes_.size());
  const int depth = nodes_[leaf].depth + 1;
  nodes_.push_back(Node{{0, 0}, slot, depth});
  nodes_.push_back(Node{{0, 0}, new_slot, depth});
  nodes_[leaf].child[0] = lower;
  nodes_[leaf].child[1] = lower + 1;
  leaf_node_[slot] = lower;
  leaf_node_.push_back(lower + 1);
  return new_slot;
}

int SpatialTree::depth_of(uint32_t slot) const { return nodes_[leaf_node_[slot]].depth; }

}  // namespace phyir::render::guiding
