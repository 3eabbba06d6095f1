#pragma once
// The spatial half of the SD-tree (Müller et al. 2017, section 3.1): a binary tree over a
// cube around the scene, each level halving its cell along x, y, z in turn. Leaves name a
// slot (an index the SD-tree keeps its quadtrees under); splitting a leaf keeps its slot for
// the lower child and gives the upper child a new one.
#include <cstdint>
#include <vector>

#include <glm/glm.hpp>

namespace phyir::render::guiding {

class SpatialTree {
 public:
  // A single leaf (slot 0) over the cube that holds [min, max], enlarged by 1% so points
  // on the bounds fall inside.
  SpatialTree(const glm::vec3& min, const glm::vec3& max);

  // The slot of the leaf holding p (points outside the cube go to the nearest leaf).
  uint32_t slot_at(const glm::vec3& p) const;

  // Splits the leaf of `slot` once; returns the upper child's new slot (== slot_count() - 1),
  // or UINT32_MAX when the leaf is at max_depth.
  uint32_t split(uint32_t slot, int max_depth);

  // The depth of slot's leaf (the root is depth 0).
  int depth_of(uint32_t slot) const;
  uint32_t slot_count() const { return uint32_t(leaf_node_.size()); }
  size_t node_count() const { return nodes_.size(); }
  const glm::vec3& cube_min() const { return min_; }
  float cube_size() const { return size_; }

 private:
  struct Node {
    uint32_t child[2] = {0, 0};  // 0: a leaf (the root is nobody's child)
    uint32_t slot = 0;           // a leaf's
    int depth = 0;
  };
  std::vector<Node> nodes_;
  std::vector<uint32_t> leaf_node_;  // per slot, its leaf
  glm::vec3 min_;
  float size_;
};

}  // namespace phyir::render::guiding
