#include "gltf_primitives.h"

#include <numeric>

#include "gltf_accessors.h"

namespace phyir::scenes::gltf {

namespace {

const char* mode_name(int mode) {
  switch (mode) {
    case TINYGLTF_MODE_POINTS:
      return "POINTS";
    case TINYGLTF_MODE_LINE:
      return "LINES";
    case TINYGLTF_MODE_LINE_LOOP:
      return "LINE_LOOP";
    case 3:
      return "LINE_STRIP";
    case TINYGLTF_MODE_TRIANGLES:
      return "TRIANGLES";
    case TINYGLTF_MODE_TRIANGLE_STRIP:
      return "TRIANGLE_STRIP";
    case TINYGLTF_MODE_TRIANGLE_FAN:
      return "TRIANGLE_FAN";
    default:
      return "unknown";
  }
}

bool draws_triangles(int mode) {
  return mode == TINYGLTF_MODE_TRIANGLES || mode == TINYGLTF_MODE_TRIANGLE_STRIP ||
         mode == TINYGLTF_MODE_TRIANGLE_FAN;
}

// Components the accessor lacks (alpha of an RGB colour) come from `fill`.
template <typename Vec>
std::vector<Vec> to_vectors(const FloatElements& elements, const Vec& fill = Vec(0.0f)) {
  std::vector<Vec> out(elements.count, fill);
  const int n = std::min(elements.components, static_cast<int>(Vec::length()));
  for (size_t i = 0; i < elements.count; ++i)
    for (int c = 0; c < n; ++c)
      out[i][c] = elements.values[i * static_cast<size_t>(elements.components) + static_cast<size_t>(c)];
  return out;
}

// Reads an optional attribute, checking that it has one element per position.
template <typename Vec>
std::vector<Vec> read_attribute(const GltfContext& ctx, const tinygltf::Primitive& primitive,
                                const char* name, const std::string& where, size_t vertex_count,
                                const FloatFormat& format, const Vec& fill = Vec(0.0f)) {
  const auto it = primitive.attributes.find(name);
  if (it == primitive.attributes.end()) return {};
  const FloatElements elements = read_floats(ctx, it->second, std::string(name) + " of " + where, format);
  if (elements.count != vertex_count)
    ctx.fail("{} attribute {} (accessor {}) has {} elements but POSITION has {}", where, name, it->second,
             elements.count, vertex_count);
  return to_vectors<Vec>(elements, fill);
}

std::vector<uint32_t> read_checked_indices(const GltfContext& ctx, const tinygltf::Primitive& primitive,
                                           const std::string& where, size_t vertex_count) {
  if (primitive.indices < 0) {
    std::vector<uint32_t> sequential(vertex_count);
    std::iota(sequential.begin(), sequential.end(), 0u);
    return sequential;
  }
  std::vector<uint32_t> indices = read_indices(ctx, primitive.indices, "indices of " + where);
  for (size_t i = 0; i < indices.size(); ++i) {
    if (indices[i] >= vertex_count)
      ctx.fail("index {} (element {} of accessor {}) is out of range for {} with {} vertices", indices[i], i,
               primitive.indices, where, vertex_count);
  }
  return indices;
}

}  // namespace

std::string primitive_label(const GltfContext& ctx, int mesh, int primitive) {
  return fmt::format("{} primitive {}", label("mesh", mesh, ctx.model.meshes), primitive);
}

std::vector<glm::uvec3> assemble_triangles(const std::vector<uint32_t>& idx, int mode) {
  std::vector<glm::uvec3> triangles;
  if (mode == TINYGLTF_MODE_TRIANGLES) {
    for (size_t i = 0; i + 2 < idx.size(); i += 3) triangles.emplace_back(idx[i], idx[i + 1], idx[i + 2]);
  } else if (mode == TINYGLTF_MODE_TRIANGLE_STRIP) {
    // Odd triangles swap their last two vertices to keep the strip's winding.
    for (size_t i = 0; i + 2 < idx.size(); ++i)
      triangles.push_back(i % 2 == 0 ? glm::uvec3(idx[i], idx[i + 1], idx[i + 2])
                                     : glm::uvec3(idx[i], idx[i + 2], idx[i + 1]));
  } else if (mode == TINYGLTF_MODE_TRIANGLE_FAN) {
    for (size_t i = 1; i + 1 < idx.size(); ++i) triangles.emplace_back(idx[i], idx[i + 1], idx[0]);
  }
  return triangles;
}

std::optional<PrimitiveData> read_primitive(const GltfContext& ctx, int mesh_index, int primitive_index) {
  const tinygltf::Primitive& primitive =
      ctx.model.meshes[static_cast<size_t>(mesh_index)].primitives[static_cast<size_t>(primitive_index)];
  const std::string where = primitive_label(ctx, mesh_index, primitive_index);
  // tinygltf reports an absent mode as -1; glTF's default is TRIANGLES.
  const int mode = primitive.mode < 0 ? TINYGLTF_MODE_TRIANGLES : primitive.mode;
  if (!draws_triangles(mode)) {
    ctx.warn("{} has mode {} ({}): skipped, only triangles are rendered", where, mode_name(mode), mode);
    return std::nullopt;
  }
  const auto position = primitive.attributes.find("POSITION");
  if (position == primitive.attributes.end()) ctx.fail("{} has no POSITION attribute", where);

  PrimitiveData data;
  data.positions = to_vectors<glm::vec3>(
      read_floats(ctx, position->second, "POSITION of " + where, {{TINYGLTF_TYPE_VEC3}}));
  const size_t n = data.positions.size();
  data.normals = read_attribute<glm::vec3>(ctx, primitive, "NORMAL", where, n, {{TINYGLTF_TYPE_VEC3}});
  data.tangents = read_attribute<glm::vec4>(ctx, primitive, "TANGENT", where, n, {{TINYGLTF_TYPE_VEC4}});
  const FloatFormat uv_format{{TINYGLTF_TYPE_VEC2}, true};
  data.texcoords0 = read_attribute<glm::vec2>(ctx, primitive, "TEXCOORD_0", where, n, uv_format);
  data.texcoords1 = read_attribute<glm::vec2>(ctx, primitive, "TEXCOORD_1", where, n, uv_format);
  const FloatFormat colour_format{{TINYGLTF_TYPE_VEC3, TINYGLTF_TYPE_VEC4}, true};
  // RGB colours are opaque.
  data.colors =
      read_attribute<glm::vec4>(ctx, primitive, "COLOR_0", where, n, colour_format, glm::vec4(0, 0, 0, 1));

  const std::vector<uint32_t> indices = read_checked_indices(ctx, primitive, where, n);
  if (mode == TINYGLTF_MODE_TRIANGLES && indices.size() % 3 != 0)
    ctx.warn("{} has {} indices, not a multiple of 3: the last {} are ignored", where, indices.size(),
             indices.size() % 3);
  data.triangles = assemble_triangles(indices, mode);
  if (!primitive.targets.empty()) ctx.warn("{} has morph targets: ignored, the base shape is used", where);
  if (data.triangles.empty()) {
    ctx.warn("{} draws no triangle ({} indices): skipped", where, indices.size());
    return std::nullopt;
  }
  return data;
}

}  // namespace phyir::scenes::gltf
