#include "gltf/read/gltf_primitives.h"

#include <algorithm>
#include <numeric>

#include "gltf/compression/gltf_draco.h"
#include "gltf/read/gltf_accessors.h"

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

// Where a primitive's attributes come from: its Draco data for the attributes the
// extension names, its accessors for the others.
class AttributeSource {
 public:
  AttributeSource(const GltfContext& ctx, const tinygltf::Primitive& primitive, const std::string& where)
      : ctx_(ctx), primitive_(primitive), where_(where) {
    if (has_draco(primitive)) draco_ = decode_draco(ctx, primitive, where);
  }

  const std::optional<DracoPrimitive>& draco() const { return draco_; }

  std::optional<FloatElements> read(const std::string& name) const {
    if (draco_) {
      const auto decoded = draco_->attributes.find(name);
      if (decoded != draco_->attributes.end()) return decoded->second;
    }
    const auto it = primitive_.attributes.find(name);
    if (it == primitive_.attributes.end()) return std::nullopt;
    return read_floats(ctx_, it->second, name + " of " + where_, attribute_format(name));
  }

  // An optional attribute, checked to have one element per position.
  template <typename Vec>
  std::vector<Vec> vectors(const std::string& name, size_t vertex_count, const Vec& fill = Vec(0.0f)) const {
    const std::optional<FloatElements> elements = read(name);
    if (!elements) return {};
    if (elements->count != vertex_count)
      ctx_.fail("{} attribute {} (accessor {}) has {} elements but POSITION has {}", where_, name,
                primitive_.attributes.at(name), elements->count, vertex_count);
    return to_vectors<Vec>(*elements, fill);
  }

 private:
  const GltfContext& ctx_;
  const tinygltf::Primitive& primitive_;
  const std::string& where_;
  std::optional<DracoPrimitive> draco_;
};

bool requires_extension(const tinygltf::Model& model, const char* name) {
  const auto& required = model.extensionsRequired;
  return std::find(required.begin(), required.end(), name) != required.end();
}

// A file that requires Draco keeps its geometry only there: an accessor without data on a
// primitive without the extension means the compressed data went missing.
void check_draco_data_present(const GltfContext& ctx, const tinygltf::Primitive& primitive,
                              const std::string& where) {
  if (has_draco(primitive) || !requires_extension(ctx.model, "KHR_draco_mesh_compression")) return;
  const int position = primitive.attributes.at("POSITION");
  if (!in_range(position, ctx.model.accessors.size())) return;  // read_floats names this error
  const tinygltf::Accessor& accessor = ctx.model.accessors[static_cast<size_t>(position)];
  if (accessor.bufferView < 0 && !accessor.sparse.isSparse)
    ctx.fail(
        "{} has no KHR_draco_mesh_compression extension and its POSITION accessor {} has no bufferView: "
        "the file requires KHR_draco_mesh_compression, so the compressed data is missing",
        where, position);
}

std::vector<uint32_t> read_checked_indices(const GltfContext& ctx, const tinygltf::Primitive& primitive,
                                           const AttributeSource& source, const std::string& where,
                                           size_t vertex_count) {
  std::vector<uint32_t> indices;
  if (source.draco()) {
    indices = source.draco()->indices;
  } else if (primitive.indices >= 0) {
    indices = read_indices(ctx, primitive.indices, "indices of " + where);
  } else {
    indices.resize(vertex_count);
    std::iota(indices.begin(), indices.end(), 0u);
    return indices;
  }
  for (size_t i = 0; i < indices.size(); ++i) {
    if (indices[i] >= vertex_count)
      ctx.fail("index {} (element {} of {}) is out of range for {} with {} vertices", indices[i], i,
               source.draco() ? "the Draco faces" : fmt::format("accessor {}", primitive.indices), where,
               vertex_count);
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

  check_draco_data_present(ctx, primitive, where);
  const AttributeSource source(ctx, primitive, where);

  PrimitiveData data;
  data.positions = to_vectors<glm::vec3>(*source.read("POSITION"));
  const size_t n = data.positions.size();
  data.normals = source.vectors<glm::vec3>("NORMAL", n);
  data.tangents = source.vectors<glm::vec4>("TANGENT", n);
  data.texcoords0 = source.vectors<glm::vec2>("TEXCOORD_0", n);
  data.texcoords1 = source.vectors<glm::vec2>("TEXCOORD_1", n);
  // RGB colours are opaque.
  data.colors = source.vectors<glm::vec4>("COLOR_0", n, glm::vec4(0, 0, 0, 1));

  const std::vector<uint32_t> indices = read_checked_indices(ctx, primitive, source, where, n);
  if (mode == TINYGLTF_MODE_TRIANGLES && indices.size() % 3 != 0)
    ctx.warn("{} has {} indices, not a multiple of 3: the last {} are ignored", where, indices.size(),
             indices.size() % 3);
  // Draco decodes faces, a triangle list whatever the mode (TRIANGLES or TRIANGLE_STRIP).
  data.triangles = assemble_triangles(indices, source.draco() ? TINYGLTF_MODE_TRIANGLES : mode);
  if (!primitive.targets.empty()) ctx.warn("{} has morph targets: ignored, the base shape is used", where);
  if (data.triangles.empty()) {
    ctx.warn("{} draws no triangle ({} indices): skipped", where, indices.size());
    return std::nullopt;
  }
  return data;
}

}  // namespace phyir::scenes::gltf
