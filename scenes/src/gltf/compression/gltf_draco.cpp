#include "gltf/compression/gltf_draco.h"

#include <draco/compression/decode.h>
#include <draco/mesh/mesh.h>

#include <cstring>
#include <memory>

#include "gltf/read/gltf_values.h"

namespace phyir::scenes::gltf {

namespace {

constexpr char kExtension[] = "KHR_draco_mesh_compression";

std::unique_ptr<draco::Mesh> decode_mesh(const GltfContext& ctx, const tinygltf::Value& ext,
                                         const std::string& where) {
  const std::optional<int> view = integer_member(ctx, ext, "bufferView", where);
  if (!view) ctx.fail("{} has no bufferView", where);
  const ByteRange bytes = view_bytes(ctx, *view, where);
  draco::DecoderBuffer buffer;
  buffer.Init(reinterpret_cast<const char*>(bytes.data), bytes.size);
  draco::Decoder decoder;
  auto decoded = decoder.DecodeMeshFromBuffer(&buffer);
  if (!decoded.ok())
    ctx.fail("{}: Draco cannot decode bufferView {} ({} bytes): {}", where, *view, bytes.size,
             decoded.status().error_msg_string());
  std::unique_ptr<draco::Mesh> mesh = std::move(decoded).value();
  if (mesh == nullptr) ctx.fail("{}: Draco decoded no mesh from bufferView {}", where, *view);
  return mesh;
}

// Every point's value converted to T, packed as the accessor's elements.
template <typename T>
bool convert_points(const draco::PointAttribute& attribute, uint32_t points, int components,
                    std::vector<unsigned char>& packed) {
  const size_t element_size = sizeof(T) * static_cast<size_t>(components);
  packed.resize(element_size * points);
  std::vector<T> element(static_cast<size_t>(components));
  for (uint32_t p = 0; p < points; ++p) {
    const draco::AttributeValueIndex value = attribute.mapped_index(draco::PointIndex(p));
    if (!attribute.ConvertValue<T>(value, static_cast<int8_t>(components), element.data())) return false;
    std::memcpy(packed.data() + p * element_size, element.data(), element_size);
  }
  return true;
}

// The attribute in the accessor's componentType; the accessor's normalized flag then
// dequantizes it exactly as if it had been stored in a bufferView.
bool convert_attribute(const draco::PointAttribute& attribute, uint32_t points, int components,
                       int component_type, std::vector<unsigned char>& packed) {
  switch (component_type) {
    case TINYGLTF_COMPONENT_TYPE_BYTE:
      return convert_points<int8_t>(attribute, points, components, packed);
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE:
      return convert_points<uint8_t>(attribute, points, components, packed);
    case TINYGLTF_COMPONENT_TYPE_SHORT:
      return convert_points<int16_t>(attribute, points, components, packed);
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT:
      return convert_points<uint16_t>(attribute, points, components, packed);
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT:
      return convert_points<uint32_t>(attribute, points, components, packed);
    default:
      return convert_points<float>(attribute, points, components, packed);
  }
}

class DracoReader {
 public:
  DracoReader(const GltfContext& ctx, const tinygltf::Primitive& primitive, const std::string& where)
      : ctx_(ctx), primitive_(primitive), where_(where), ext_where_(where + " " + kExtension) {}

  DracoPrimitive read() {
    const tinygltf::Value& ext = primitive_.extensions.at(kExtension);
    if (!ext.IsObject()) ctx_.fail("{} is not a JSON object", ext_where_);
    const tinygltf::Value* ids = member(ext, "attributes");
    if (ids == nullptr || !ids->IsObject()) ctx_.fail("{} has no attributes object", ext_where_);
    mesh_ = decode_mesh(ctx_, ext, ext_where_);
    DracoPrimitive out;
    for (const std::string& name : ids->Keys()) {
      const draco::PointAttribute& attribute = find_attribute(name, ids->Get(name));
      if (!attribute_format(name).types.empty()) out.attributes[name] = read_attribute(name, attribute);
    }
    out.indices = read_faces();
    return out;
  }

 private:
  const draco::PointAttribute& find_attribute(const std::string& name, const tinygltf::Value& id) const {
    if (!id.IsInt() || id.GetNumberAsInt() < 0)
      ctx_.fail("{} attribute {} id is not a non-negative integer", ext_where_, name);
    if (primitive_.attributes.count(name) == 0)
      ctx_.fail("{} names attribute {}, which the primitive does not have", ext_where_, name);
    const draco::PointAttribute* attribute =
        mesh_->GetAttributeByUniqueId(static_cast<uint32_t>(id.GetNumberAsInt()));
    if (attribute == nullptr)
      ctx_.fail("{} attribute {} has id {}, which the decoded Draco mesh does not have ({} attributes)",
                ext_where_, name, id.GetNumberAsInt(), mesh_->num_attributes());
    return *attribute;
  }

  FloatElements read_attribute(const std::string& name, const draco::PointAttribute& attribute) const {
    const int index = primitive_.attributes.at(name);
    const std::string role = name + " of " + where_;
    const tinygltf::Accessor& accessor = check_float_accessor(ctx_, index, role, attribute_format(name));
    const int components = tinygltf::GetNumComponentsInType(static_cast<uint32_t>(accessor.type));
    const uint32_t points = mesh_->num_points();
    if (accessor.count != points)
      ctx_.fail("{} has count {} but the decoded Draco mesh has {} points", accessor_label(index, role),
                accessor.count, points);
    if (attribute.num_components() != components)
      ctx_.fail("{}: Draco attribute {} has {} components, the accessor {}", accessor_label(index, role),
                attribute.unique_id(), attribute.num_components(), components);
    if (!attribute.is_mapping_identity() && attribute.indices_map_size() < points)
      ctx_.fail("{}: Draco attribute {} maps {} of {} points", accessor_label(index, role),
                attribute.unique_id(), attribute.indices_map_size(), points);
    std::vector<unsigned char> packed;
    if (!convert_attribute(attribute, points, components, accessor.componentType, packed))
      ctx_.fail("{}: Draco attribute {} does not convert to {}", accessor_label(index, role),
                attribute.unique_id(), component_name(accessor.componentType));
    return floats_from_packed(ctx_, index, role, packed);
  }

  std::vector<uint32_t> read_faces() const {
    const uint32_t faces = mesh_->num_faces();
    const int mode = primitive_.mode < 0 ? TINYGLTF_MODE_TRIANGLES : primitive_.mode;
    if (primitive_.indices >= 0 && mode == TINYGLTF_MODE_TRIANGLES) {
      const std::string role = "indices of " + where_;
      if (!in_range(primitive_.indices, ctx_.model.accessors.size()))
        ctx_.fail("{} refers to accessor {}, which does not exist ({} accessors)", role, primitive_.indices,
                  ctx_.model.accessors.size());
      const size_t count = ctx_.model.accessors[static_cast<size_t>(primitive_.indices)].count;
      if (count != size_t{faces} * 3)
        ctx_.fail("{} has count {} but the decoded Draco mesh has {} triangles ({} indices)",
                  accessor_label(primitive_.indices, role), count, faces, size_t{faces} * 3);
    }
    std::vector<uint32_t> indices;
    indices.reserve(size_t{faces} * 3);
    for (uint32_t f = 0; f < faces; ++f)
      for (const draco::PointIndex& point : mesh_->face(draco::FaceIndex(f)))
        indices.push_back(point.value());
    return indices;
  }

  const GltfContext& ctx_;
  const tinygltf::Primitive& primitive_;
  const std::string& where_;
  const std::string ext_where_;
  std::unique_ptr<draco::Mesh> mesh_;
};

}  // namespace

bool has_draco(const tinygltf::Primitive& primitive) { return primitive.extensions.count(kExtension) != 0; }

DracoPrimitive decode_draco(const GltfContext& ctx, const tinygltf::Primitive& primitive,
                            const std::string& where) {
  return DracoReader(ctx, primitive, where).read();
}

}  // namespace phyir::scenes::gltf
