#pragma once
// The triangles of one emissive cluster (emitter_sampler.h) in a binary tree of bounding
// boxes, for choosing a triangle by how much it may light a given point rather than by its
// power alone. Near a lamp of a thousand glowing triangles (a ceiling fixture's canopy
// touching the ceiling), the few triangles millimetres from a shaded point give it most of
// its light, yet hold a thousandth of the power: chosen by power, light samples almost
// never find them and a BRDF-sampled ray that does carries the whole light (measured on the
// night apartment: texels of the ceiling beside a fixture read 1.2 or 0.01 by the luck of
// that one ray). Descending the tree, each child is taken with probability proportional to
// a bound of the irradiance it can give the point: power / d^2, d the distance to the
// nearest point of its box, but at most 2 pi x its mean radiance (all the light a surface
// of that radiance filling a hemisphere gives). Far from the cluster that is its power
// share; beside it, the nearby triangles, and among those that surround the point, the
// brighter. Where a subtree's triangles are parallel (a flat panel's, a canopy's disc), light
// leaves them at a cosine of at most h / d, h the point's largest height above their planes:
// seen 1 mm from a panel, its far parts get that much less.
#include <glm/glm.hpp>

#include <vector>

namespace phyir::render {

class EmitterTree {
 public:
  // What the tree needs of a triangle: its bounds, area and power (area x emitted luminance).
  struct Item {
    glm::vec3 lo{0.0f}, hi{0.0f};
    float area = 0.0f;
    float power = 0.0f;
    glm::vec3 normal{0.0f, 1.0f, 0.0f};  // unit
  };

  EmitterTree() = default;
  // Items of power <= 0 are never chosen.
  explicit EmitterTree(const std::vector<Item>& items);

  bool empty() const { return nodes_.empty(); }

  // An item chosen from `reference` with u in [0, 1); its probability in *pmf. -1 if none
  // can be chosen.
  int sample(const glm::vec3& reference, float u, float* pmf) const;
  // The probability sample() chooses `item` from `reference`: bit-identical to its *pmf.
  float pmf(const glm::vec3& reference, int item) const;

 private:
  struct Node {
    glm::vec3 lo{0.0f}, hi{0.0f};
    float power = 0.0f;
    float radiance = 0.0f;  // power / area: its mean emitted luminance
    glm::vec3 axis{0.0f};   // the triangles' common normal (up to sign) where they share one, else 0
    float offset_lo = 0.0f, offset_hi = 0.0f;  // the range of dot(axis, q) over the box
    int left = -1, right = -1;  // children; both -1 for a leaf
    int item = -1;              // a leaf's item
    int parent = -1;
  };
  static Node summary(const std::vector<int>& order, size_t begin, size_t end, const std::vector<Item>& items);
  int build(std::vector<int>& order, size_t begin, size_t end, const std::vector<Item>& items, int parent);
  float importance(const Node& node, const glm::vec3& reference) const;
  // The probability of taking the left child of `node` from `reference`.
  float left_probability(const Node& node, const glm::vec3& reference) const;

  std::vector<Node> nodes_;  // nodes_[0] is the root
  std::vector<int> leaf_of_item_;
};

}  // namespace phyir::render
