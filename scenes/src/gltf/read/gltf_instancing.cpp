#include "gltf/read/gltf_instancing.h"

#include <glm/gtc/matrix_transform.hpp>
#include <glm/gtc/quaternion.hpp>

#include "gltf/read/gltf_geometry.h"
#include "gltf/read/gltf_values.h"

namespace phyir::scenes::gltf {

namespace {

constexpr const char* kGpuInstancing = "EXT_mesh_gpu_instancing";

std::string extension_label(const GltfContext& ctx, int node) {
  return fmt::format("{} {}", label("node", node, ctx.model.nodes), kGpuInstancing);
}

// The accessor attribute `name` names, checked to exist.
int attribute_accessor(const GltfContext& ctx, const tinygltf::Value& attributes, const std::string& name,
                       const std::string& where) {
  const int accessor = *integer_member(ctx, attributes, name, where + " attributes");
  if (!in_range(accessor, ctx.model.accessors.size()))
    ctx.fail("{} attribute {} refers to accessor {}, which does not exist ({} accessors)", where, name, accessor,
             ctx.model.accessors.size());
  return accessor;
}

// The extension's accessor formats: FLOAT, and for ROTATION normalized BYTE / SHORT too.
FloatFormat instance_attribute_format(int type) {
  FloatFormat format{{type}, {}, {}};
  if (type == TINYGLTF_TYPE_VEC4)
    format.core = {{TINYGLTF_COMPONENT_TYPE_BYTE, true}, {TINYGLTF_COMPONENT_TYPE_SHORT, true}};
  return format;
}

FloatElements read_attribute(const GltfContext& ctx, int accessor, const char* name, const std::string& where,
                             int type) {
  if (accessor < 0) return {};
  return read_floats(ctx, accessor, fmt::format("{} of {}", name, where), instance_attribute_format(type));
}

glm::dquat rotation(const FloatElements& rotations, size_t i) {
  const float* q = &rotations.values[4 * i];
  return glm::dquat(q[3], q[0], q[1], q[2]);  // glTF stores (x, y, z, w); glm takes w first
}

// Rotations are normalised when used, as the node's own are (gltf_nodes.cpp); a zero
// quaternion has no direction to normalise to.
void check_rotations(const GltfContext& ctx, const FloatElements& rotations, const std::string& where) {
  for (size_t i = 0; i < rotations.count; ++i)
    if (!(glm::length(rotation(rotations, i)) > 1e-12))
      ctx.fail("{} instance {} ROTATION is a zero quaternion", where, i);
}

// Appends `part`, its triangles renumbered past the vertices already in `whole`.
void append(Mesh& whole, const Mesh& part) {
  const auto first = static_cast<uint32_t>(whole.positions.size());
  auto extend = [](auto& to, const auto& from) { to.insert(to.end(), from.begin(), from.end()); };
  extend(whole.positions, part.positions);
  extend(whole.normals, part.normals);
  extend(whole.tangents, part.tangents);
  extend(whole.texcoords0, part.texcoords0);
  extend(whole.texcoords1, part.texcoords1);
  extend(whole.colors, part.colors);
  for (const glm::uvec3& t : part.triangles) whole.triangles.push_back(t + first);
}

void reserve_copies(Mesh& whole, const Mesh& one, size_t copies) {
  whole.positions.reserve(one.positions.size() * copies);
  whole.normals.reserve(one.normals.size() * copies);
  whole.tangents.reserve(one.tangents.size() * copies);
  whole.texcoords0.reserve(one.texcoords0.size() * copies);
  whole.texcoords1.reserve(one.texcoords1.size() * copies);
  whole.colors.reserve(one.colors.size() * copies);
  whole.triangles.reserve(one.triangles.size() * copies);
}

}  // namespace

std::optional<InstanceAttributes> find_gpu_instancing(const GltfContext& ctx, int node) {
  const tinygltf::Node& source = ctx.model.nodes[static_cast<size_t>(node)];
  const auto found = source.extensions.find(kGpuInstancing);
  if (found == source.extensions.end()) return std::nullopt;
  const std::string where = extension_label(ctx, node);
  if (source.mesh < 0) {
    ctx.warn("{} ignored: the node has no mesh", where);
    return std::nullopt;
  }
  const tinygltf::Value* attributes = member(found->second, "attributes");
  if (attributes == nullptr || !attributes->IsObject() || attributes->Keys().empty())
    ctx.fail("{} has no attributes (an object naming at least one accessor)", where);

  InstanceAttributes out;
  std::string first;  // the attribute whose count the others must match
  for (const std::string& name : attributes->Keys()) {
    const int accessor = attribute_accessor(ctx, *attributes, name, where);
    const size_t count = ctx.model.accessors[static_cast<size_t>(accessor)].count;
    if (first.empty()) {
      first = name;
      out.count = count;
    } else if (count != out.count) {
      ctx.fail("{} attribute {} (accessor {}) has count {} but {} has count {}: all must be equal", where, name,
               accessor, count, first, out.count);
    }
    // Custom attributes ("_ID") are the application's; only their count matters here.
    if (name == "TRANSLATION")
      out.translation = accessor;
    else if (name == "ROTATION")
      out.rotation = accessor;
    else if (name == "SCALE")
      out.scale = accessor;
    else if (name.rfind('_', 0) != 0)
      ctx.warn("{} attribute {} is not in the extension: ignored", where, name);
  }
  return out;
}

InstanceTransforms::InstanceTransforms(const GltfContext& ctx, const NodeInstance& node,
                                       const InstanceAttributes& attributes)
    : world_(node.world), count_(attributes.count) {
  const std::string where = extension_label(ctx, node.node);
  translations_ = read_attribute(ctx, attributes.translation, "TRANSLATION", where, TINYGLTF_TYPE_VEC3);
  rotations_ = read_attribute(ctx, attributes.rotation, "ROTATION", where, TINYGLTF_TYPE_VEC4);
  scales_ = read_attribute(ctx, attributes.scale, "SCALE", where, TINYGLTF_TYPE_VEC3);
  check_rotations(ctx, rotations_, where);
}

glm::dmat4 InstanceTransforms::world(size_t i) const {
  // Translation * rotation * scale, as for a node (gltf_nodes.cpp local_transform).
  glm::dmat4 m = world_;
  if (!translations_.values.empty()) {
    const float* t = &translations_.values[3 * i];
    m = glm::translate(m, glm::dvec3(t[0], t[1], t[2]));
  }
  if (!rotations_.values.empty()) m *= glm::mat4_cast(glm::normalize(rotation(rotations_, i)));
  if (!scales_.values.empty()) {
    const float* s = &scales_.values[3 * i];
    m = glm::scale(m, glm::dvec3(s[0], s[1], s[2]));
  }
  return m;
}

Mesh bake_instances(const PrimitiveData& local, const InstanceTransforms& instances) {
  Mesh whole;
  for (size_t i = 0; i < instances.size(); ++i) {
    const Mesh one = bake_to_world(local, instances.world(i));
    if (i == 0) reserve_copies(whole, one, instances.size());
    append(whole, one);
  }
  return whole;
}

}  // namespace phyir::scenes::gltf
