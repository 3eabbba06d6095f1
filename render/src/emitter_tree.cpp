#include "phyir/render/emitter_tree.h"

#include <algorithm>
#include <cmath>

#include "phyir/core/safe_math.h"
#include "phyir/render/sampling.h"
#include "phyir/scenes/scene.h"

namespace phyir::render {

namespace {

// A path from the root to a leaf: a median split halves the items, so 64 levels hold any mesh.
constexpr int kMaxDepth = 64;

// Normals this close (|cos| above it) count as parallel.
constexpr float kParallel = 0.9999f;

glm::vec3 centroid(const EmitterTree::Item& item) { return 0.5f * (item.lo + item.hi); }

}  // namespace

EmitterTree::EmitterTree(const std::vector<Item>& items) {
  leaf_of_item_.assign(items.size(), -1);
  std::vector<int> order;
  for (size_t i = 0; i < items.size(); ++i)
    if (items[i].power > 0.0f && std::isfinite(items[i].power)) order.push_back(int(i));
  if (order.empty()) return;
  nodes_.reserve(2 * order.size());
  build(order, 0, order.size(), items, -1);
}

// What a subtree's importance needs of its items: bounds, power, mean radiance, and their
// common normal where they are parallel, with the box's range of offsets along it.
EmitterTree::Node EmitterTree::summary(const std::vector<int>& order, size_t begin, size_t end,
                                       const std::vector<Item>& items) {
  Node node;
  scenes::Bounds box;
  float area = 0.0f;
  node.axis = items[size_t(order[begin])].normal;
  for (size_t k = begin; k < end; ++k) {
    const Item& item = items[size_t(order[k])];
    box.extend(item.lo);
    box.extend(item.hi);
    node.power += item.power;
    area += item.area;
    if (!(std::abs(glm::dot(node.axis, item.normal)) > kParallel)) node.axis = glm::vec3(0.0f);
  }
  node.lo = box.min;
  node.hi = box.max;
  node.radiance = safe_div(node.power, area);
  for (int corner = 0; corner < 8; ++corner) {
    const glm::vec3 q((corner & 1) ? node.hi.x : node.lo.x, (corner & 2) ? node.hi.y : node.lo.y,
                      (corner & 4) ? node.hi.z : node.lo.z);
    const float offset = glm::dot(node.axis, q);
    node.offset_lo = corner == 0 ? offset : std::min(node.offset_lo, offset);
    node.offset_hi = corner == 0 ? offset : std::max(node.offset_hi, offset);
  }
  return node;
}

// Median split along the widest axis of the centroids; ties by index, so the tree depends
// on the items alone.
int EmitterTree::build(std::vector<int>& order, size_t begin, size_t end, const std::vector<Item>& items, int parent) {
  const int index = int(nodes_.size());
  nodes_.emplace_back();
  Node node = summary(order, begin, end, items);
  node.parent = parent;
  if (end - begin == 1) {
    node.item = order[begin];
    leaf_of_item_[size_t(node.item)] = index;
    nodes_[size_t(index)] = node;
    return index;
  }
  scenes::Bounds centroids;
  for (size_t k = begin; k < end; ++k) centroids.extend(centroid(items[size_t(order[k])]));
  const glm::vec3 extent = centroids.max - centroids.min;
  const int axis = extent.x >= extent.y && extent.x >= extent.z ? 0 : (extent.y >= extent.z ? 1 : 2);
  const size_t mid = begin + (end - begin) / 2;
  std::nth_element(order.begin() + long(begin), order.begin() + long(mid), order.begin() + long(end), [&](int a, int b) {
    const float ca = centroid(items[size_t(a)])[axis], cb = centroid(items[size_t(b)])[axis];
    return ca < cb || (ca == cb && a < b);
  });
  node.left = build(order, begin, mid, items, index);
  node.right = build(order, mid, end, items, index);
  nodes_[size_t(index)] = node;
  return index;
}

float EmitterTree::importance(const Node& node, const glm::vec3& reference) const {
  const glm::vec3 d = glm::clamp(reference, node.lo, node.hi) - reference;
  const float d2 = glm::dot(d, d), hemisphere = kTwoPi * node.radiance;
  const float bound = d2 * hemisphere > node.power ? node.power / d2 : hemisphere;  // inside its box: d2 = 0
  if (node.axis == glm::vec3(0.0f) || !(d2 > 0.0f)) return bound;
  // Parallel triangles: cos at the emitter <= h / d, h the point's largest height over the
  // planes through the box (its corners' offsets along the axis).
  const float height = glm::dot(node.axis, reference);
  const float h = std::max(std::abs(height - node.offset_lo), std::abs(height - node.offset_hi));
  return bound * std::min(1.0f, h / std::sqrt(d2));
}

float EmitterTree::left_probability(const Node& node, const glm::vec3& reference) const {
  const Node& left = nodes_[size_t(node.left)];
  const Node& right = nodes_[size_t(node.right)];
  const float l = importance(left, reference), r = importance(right, reference);
  const float total = l + r;
  // Unreachable for finite scenes; then by power, which is always defined.
  if (!(total > 0.0f) || !std::isfinite(total)) return safe_div(left.power, left.power + right.power);
  return l / total;
}

int EmitterTree::sample(const glm::vec3& reference, float u, float* pmf) const {
  *pmf = 0.0f;
  if (nodes_.empty()) return -1;
  float p = 1.0f;
  int n = 0;
  while (nodes_[size_t(n)].item < 0) {
    const Node& node = nodes_[size_t(n)];
    const float p_left = left_probability(node, reference);
    if (u < p_left) {
      p *= p_left;
      u = u / p_left;
      n = node.left;
    } else {
      p *= 1.0f - p_left;
      u = safe_div(u - p_left, 1.0f - p_left);
      n = node.right;
    }
    u = std::clamp(u, 0.0f, kOneMinusEpsilon);
  }
  *pmf = p;
  return p > 0.0f ? nodes_[size_t(n)].item : -1;
}

float EmitterTree::pmf(const glm::vec3& reference, int item) const {
  if (item < 0 || size_t(item) >= leaf_of_item_.size() || leaf_of_item_[size_t(item)] < 0) return 0.0f;
  int path[kMaxDepth];
  int depth = 0;
  for (int n = leaf_of_item_[size_t(item)]; n >= 0 && depth < kMaxDepth; n = nodes_[size_t(n)].parent) path[depth++] = n;
  // Multiplied from the root down, as sample() does, so the two agree bit for bit.
  float p = 1.0f;
  for (int k = depth - 1; k > 0; --k) {
    const Node& node = nodes_[size_t(path[k])];
    const float p_left = left_probability(node, reference);
    p *= path[k - 1] == node.left ? p_left : 1.0f - p_left;
  }
  return p;
}

}  // namespace phyir::render
