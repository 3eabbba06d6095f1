#include "phyir/render/guiding/directional_quadtree.h"

#include <algorithm>

#include "phyir/render/guiding/cylindrical_map.h"

namespace phyir::render::guiding {

namespace {

int child_of(const glm::dvec2& p) { return (p.x >= 0.5 ? 1 : 0) | (p.y >= 0.5 ? 2 : 0); }

// p in the parent's cell, in the child's.
glm::dvec2 into_child(const glm::dvec2& p, int c) {
  return glm::dvec2(2.0 * p.x - (c & 1 ? 1.0 : 0.0), 2.0 * p.y - (c & 2 ? 1.0 : 0.0));
}

// u in [0, 1) split at lower / (lower + upper): which side, and u rescaled into [0, 1) on it.
bool pick_upper(double* u, double lower, double upper) {
  const double share = lower + upper > 0.0 ? lower / (lower + upper) : 0.5;
  if (*u < share) {
    *u = share > 0.0 ? *u / share : 0.0;
    return false;
  }
  *u = share < 1.0 ? (*u - share) / (1.0 - share) : 0.0;
  *u = std::min(*u, 1.0 - 1e-12);
  return true;
}

}  // namespace

DirectionalQuadtree::DirectionalQuadtree() : nodes_(1) {}

void DirectionalQuadtree::record(const glm::vec2& p_float, double value) {
  glm::dvec2 p(std::clamp(p_float.x, 0.0f, 1.0f), std::clamp(p_float.y, 0.0f, 1.0f));
  uint32_t node = 0;
  for (;;) {
    const int c = child_of(p);
    nodes_[node].energy[c] += value;
    if (nodes_[node].child[c] == 0) return;
    node = nodes_[node].child[c];
    p = into_child(p, c);
  }
}

double DirectionalQuadtree::total() const { return nodes_[0].sum(); }

void DirectionalQuadtree::finalize() {
  for (Node& n : nodes_) {
    const double sum = n.sum();
    for (int c = 0; c < 4; ++c) n.share[c] = sum > 0.0 ? float(n.energy[c] / sum) : 0.25f;
  }
}

float DirectionalQuadtree::pdf_square(const glm::vec2& p_float) const {
  glm::vec2 p(std::clamp(p_float.x, 0.0f, 1.0f), std::clamp(p_float.y, 0.0f, 1.0f));
  float pdf = 1.0f;
  uint32_t node = 0;
  for (;;) {
    const Node& n = nodes_[node];
    const int c = (p.x >= 0.5f ? 1 : 0) | (p.y >= 0.5f ? 2 : 0);
    pdf *= 4.0f * n.share[c];
    if (n.child[c] == 0 || !(pdf > 0.0f)) return pdf;
    node = n.child[c];
    // Doubling is exact in float: the cell found is the one the double-precision map finds.
    p = glm::vec2(2.0f * p.x - float(c & 1), 2.0f * p.y - float((c >> 1) & 1));
  }
}

glm::vec2 DirectionalQuadtree::sample_square(const glm::vec2& u_float) const {
  glm::dvec2 u = glm::clamp(glm::dvec2(u_float), 0.0, 1.0 - 1e-12);
  glm::dvec2 origin(0.0);
  double size = 1.0;
  uint32_t node = 0;
  for (;;) {
    const Node& n = nodes_[node];
    // The column (x half) by its share, then the row within it.
    const double left = double(n.share[0]) + n.share[2], right = double(n.share[1]) + n.share[3];
    const int x = pick_upper(&u.x, left, right) ? 1 : 0;
    const double bottom = n.share[x], top = n.share[x + 2];
    const int y = pick_upper(&u.y, bottom, top) ? 1 : 0;
    const int c = x | (y << 1);
    size *= 0.5;
    origin += size * glm::dvec2(x, y);
    if (n.child[c] == 0) return glm::vec2(origin + size * u);
    node = n.child[c];
  }
}

float DirectionalQuadtree::pdf(const glm::vec3& direction) const {
  return pdf_square(direction_to_square(direction)) / kSphereArea;
}

glm::vec3 DirectionalQuadtree::sample(const glm::vec2& u) const { return square_to_direction(sample_square(u)); }

DirectionalQuadtree DirectionalQuadtree::refined(float threshold, int max_depth) const {
  DirectionalQuadtree tree;
  const double sum = total();
  if (!(sum > 0.0)) return tree;
  refine_into(&tree, 0, 0, nodes_[0].energy, sum, threshold, 1, max_depth);
  return tree;
}

// Builds out's new_node's children, whose energies in this tree are child_energy; old_node is the
// matching node of this tree, or UINT32_MAX where this tree was a leaf (its energy is then
// spread evenly over the quarters).
void DirectionalQuadtree::refine_into(DirectionalQuadtree* out, uint32_t old_node, uint32_t new_node,
                                      const std::array<double, 4>& child_energy, double total, float threshold,
                                      int depth, int max_depth) const {
  for (int c = 0; c < 4; ++c) {
    if (depth >= max_depth || !(child_energy[c] > threshold * total)) continue;
    const uint32_t old_child = old_node == UINT32_MAX ? UINT32_MAX : nodes_[old_node].child[c];
    const bool old_has_child = old_child != UINT32_MAX && old_child != 0;
    std::array<double, 4> grandchildren;
    grandchildren.fill(child_energy[c] / 4.0);
    if (old_has_child) grandchildren = nodes_[old_child].energy;
    const uint32_t index = uint32_t(out->nodes_.size());
    out->nodes_.emplace_back();
    out->nodes_[new_node].child[c] = index;
    refine_into(out, old_has_child ? old_child : UINT32_MAX, index, grandchildren, total, threshold, depth + 1,
                max_depth);
  }
}

int DirectionalQuadtree::depth() const { return depth_below(0); }

int DirectionalQuadtree::depth_below(uint32_t node) const {
  int deepest = 0;
  for (uint32_t child : nodes_[node].child)
    if (child != 0) deepest = std::max(deepest, depth_below(child));
  return deepest + 1;
}

}  // namespace phyir::render::guiding
