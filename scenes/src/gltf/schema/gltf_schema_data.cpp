// Buffers, buffer views and accessors (glTF 2.0 schema: buffer, bufferView, accessor*).
#include <fmt/format.h>

#include <map>

#include "gltf/schema/gltf_schema_objects.h"

namespace phyir::scenes::gltf::schema {

namespace {

constexpr long long kFloat = 5126, kUnsignedInt = 5125;

// accessor.type and its number of components, which min and max have one value for.
const std::map<std::string, size_t>& accessor_types() {
  static const std::map<std::string, size_t> types = {{"SCALAR", 1}, {"VEC2", 2}, {"VEC3", 3}, {"VEC4", 4},
                                                      {"MAT2", 4},   {"MAT3", 9}, {"MAT4", 16}};
  return types;
}

std::set<std::string> accessor_type_names() {
  std::set<std::string> names;
  for (const auto& [name, components] : accessor_types()) names.insert(name);
  return names;
}

// Spec 3.6.2.1: normalized "MUST NOT be set to true for accessors with FLOAT or UNSIGNED_INT".
void check_normalized(const Object& accessor) {
  if (!accessor.boolean("normalized") || !accessor.value().at("normalized").get<bool>()) return;
  const double component = accessor.value().at("componentType").get<double>();
  if (component == kFloat || component == kUnsignedInt)
    accessor.fail_spec("normalized", fmt::format("is true for componentType {}", component),
                       "only 8- and 16-bit integer components may be normalized");
}

// min and max: 1 to 16 numbers (schema), one per component of the type (spec 5.1.7).
void check_bounds(const Object& accessor, const char* key, const std::string& type) {
  const std::optional<size_t> length = accessor.number_array(key, Length{1, 16});
  const size_t components = accessor_types().at(type);
  if (length && *length != components)
    accessor.fail_spec(key, fmt::format("has {} items", *length),
                       fmt::format("must have {}, one per component of {}", components, type));
}

void check_sparse_indices(const Object& indices) {
  indices.required("bufferView");
  indices.index("bufferView");
  indices.integer("byteOffset", at_least(0));
  indices.required("componentType");
  indices.integer_enum("componentType", {5121, 5123, 5125});
}

void check_sparse_values(const Object& values) {
  values.required("bufferView");
  values.index("bufferView");
  values.integer("byteOffset", at_least(0));
}

void check_sparse(const Object& sparse) {
  sparse.required("count");
  sparse.integer("count", at_least(1));
  sparse.required("indices");
  sparse.object("indices", "accessor.sparse.indices", check_sparse_indices);
  sparse.required("values");
  sparse.object("values", "accessor.sparse.values", check_sparse_values);
}

}  // namespace

void check_buffer(const Object& buffer) {
  buffer.string("uri");
  buffer.required("byteLength");
  buffer.integer("byteLength", at_least(1));
  check_buffer_extensions(buffer);
}

void check_buffer_view(const Object& view) {
  view.required("buffer");
  view.index("buffer");
  view.integer("byteOffset", at_least(0));
  view.required("byteLength");
  view.integer("byteLength", at_least(1));
  const std::optional<double> stride = view.integer("byteStride", Range{4, false, 252, false});
  if (stride && static_cast<long long>(*stride) % 4 != 0)
    view.fail("byteStride", is(view.value().at("byteStride")), "must be a multiple of 4");
  view.integer_enum("target", {34962, 34963});
  check_buffer_view_extensions(view);
}

void check_accessor(const Object& accessor) {
  accessor.index("bufferView");
  accessor.integer("byteOffset", at_least(0));
  accessor.depends_on("byteOffset", "bufferView");
  accessor.required("componentType");
  accessor.integer_enum("componentType", {5120, 5121, 5122, 5123, 5125, kFloat});
  check_normalized(accessor);
  accessor.required("count");
  accessor.integer("count", at_least(1));
  accessor.required("type");
  const std::string type = *accessor.string_enum("type", accessor_type_names());
  check_bounds(accessor, "min", type);
  check_bounds(accessor, "max", type);
  accessor.object("sparse", "accessor.sparse", check_sparse);
}

}  // namespace phyir::scenes::gltf::schema
