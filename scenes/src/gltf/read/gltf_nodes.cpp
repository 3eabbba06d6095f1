#include "gltf/read/gltf_nodes.h"

#include <glm/gtc/matrix_transform.hpp>
#include <glm/gtc/quaternion.hpp>
#include <glm/gtc/type_ptr.hpp>

#include <cmath>

namespace phyir::scenes::gltf {

namespace {

void check_length(const GltfContext& ctx, int node, const char* property, const std::vector<double>& values,
                  size_t expected) {
  if (!values.empty() && values.size() != expected)
    ctx.fail("{} {} has {} numbers, expected {}", label("node", node, ctx.model.nodes), property,
             values.size(), expected);
  for (double v : values)
    if (!std::isfinite(v))
      ctx.fail("{} {} holds a non-finite number", label("node", node, ctx.model.nodes), property);
}

}  // namespace

int default_scene_index(const GltfContext& ctx) {
  const auto& model = ctx.model;
  if (model.defaultScene >= 0) {
    if (!in_range(model.defaultScene, model.scenes.size()))
      ctx.fail("default scene {} does not exist ({} scenes)", model.defaultScene, model.scenes.size());
    return model.defaultScene;
  }
  return model.scenes.empty() ? -1 : 0;
}

std::vector<int> scene_roots(const GltfContext& ctx, int scene) {
  if (scene >= 0) return ctx.model.scenes[static_cast<size_t>(scene)].nodes;
  std::vector<bool> is_child(ctx.model.nodes.size(), false);
  for (const tinygltf::Node& node : ctx.model.nodes)
    for (int child : node.children)
      if (in_range(child, is_child.size())) is_child[static_cast<size_t>(child)] = true;
  std::vector<int> roots;
  for (size_t i = 0; i < is_child.size(); ++i)
    if (!is_child[i]) roots.push_back(static_cast<int>(i));
  // Without a scene every node must hang below a root; one that cannot be reached from any
  // root lies on (or below) a cycle of children and would silently vanish.
  std::vector<bool> reached(ctx.model.nodes.size(), false);
  std::vector<int> stack = roots;
  while (!stack.empty()) {
    const int node = stack.back();
    stack.pop_back();
    if (reached[static_cast<size_t>(node)]) continue;
    reached[static_cast<size_t>(node)] = true;
    for (int child : ctx.model.nodes[static_cast<size_t>(node)].children)
      if (in_range(child, reached.size()) && !reached[static_cast<size_t>(child)]) stack.push_back(child);
  }
  for (size_t i = 0; i < reached.size(); ++i)
    if (!reached[i])
      ctx.fail("{} is on a cycle of children (the file has no scene, and its nodes do not form a tree)",
               label("node", static_cast<int>(i), ctx.model.nodes));
  return roots;
}

glm::dmat4 local_transform(const GltfContext& ctx, int index) {
  const tinygltf::Node& node = ctx.model.nodes[static_cast<size_t>(index)];
  check_length(ctx, index, "matrix", node.matrix, 16);
  if (node.matrix.size() == 16) return glm::make_mat4(node.matrix.data());  // column-major, as glm
  check_length(ctx, index, "translation", node.translation, 3);
  check_length(ctx, index, "rotation", node.rotation, 4);
  check_length(ctx, index, "scale", node.scale, 3);
  glm::dmat4 m(1.0);
  if (!node.translation.empty())
    m = glm::translate(m, glm::dvec3(node.translation[0], node.translation[1], node.translation[2]));
  if (!node.rotation.empty()) {
    // glTF stores (x, y, z, w); glm's constructor takes w first.
    const glm::dquat q(node.rotation[3], node.rotation[0], node.rotation[1], node.rotation[2]);
    if (!(glm::length(q) > 1e-12))
      ctx.fail("{} rotation is a zero quaternion", label("node", index, ctx.model.nodes));
    m *= glm::mat4_cast(glm::normalize(q));
  }
  if (!node.scale.empty()) m = glm::scale(m, glm::dvec3(node.scale[0], node.scale[1], node.scale[2]));
  return m;
}

std::vector<NodeInstance> flatten_nodes(const GltfContext& ctx, const std::vector<int>& roots) {
  const auto& nodes = ctx.model.nodes;
  std::vector<bool> reached(nodes.size(), false);
  std::vector<NodeInstance> out;
  // Explicit stack: a long chain of nodes in a hostile file must not overflow the call stack.
  std::vector<NodeInstance> stack;
  for (auto it = roots.rbegin(); it != roots.rend(); ++it) stack.push_back({*it, glm::dmat4(1.0)});
  while (!stack.empty()) {
    const NodeInstance parent = stack.back();
    stack.pop_back();
    if (!in_range(parent.node, nodes.size()))
      ctx.fail("node {} does not exist ({} nodes)", parent.node, nodes.size());
    if (reached[static_cast<size_t>(parent.node)])
      ctx.fail(
          "{} is reached twice from the scene (a node has at most one parent and is not its own ancestor)",
          label("node", parent.node, nodes));
    reached[static_cast<size_t>(parent.node)] = true;
    const NodeInstance instance{parent.node, parent.world * local_transform(ctx, parent.node)};
    out.push_back(instance);
    const std::vector<int>& children = nodes[static_cast<size_t>(instance.node)].children;
    for (auto it = children.rbegin(); it != children.rend(); ++it) stack.push_back({*it, instance.world});
  }
  return out;
}

}  // namespace phyir::scenes::gltf
