#include "gltf/read/gltf_accessors.h"

#include <fmt/ranges.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <functional>
#include <limits>

namespace phyir::scenes::gltf {

namespace {

using ElementVisitor = std::function<void(size_t element, const unsigned char* bytes)>;

const char* type_name(int type) {
  switch (type) {
    case TINYGLTF_TYPE_SCALAR:
      return "SCALAR";
    case TINYGLTF_TYPE_VEC2:
      return "VEC2";
    case TINYGLTF_TYPE_VEC3:
      return "VEC3";
    case TINYGLTF_TYPE_VEC4:
      return "VEC4";
    case TINYGLTF_TYPE_MAT2:
      return "MAT2";
    case TINYGLTF_TYPE_MAT3:
      return "MAT3";
    case TINYGLTF_TYPE_MAT4:
      return "MAT4";
    default:
      return "invalid";
  }
}

// offset + (count - 1) * stride + element_size, saturating instead of overflowing.
size_t bytes_spanned(size_t offset, size_t count, size_t stride, size_t element_size) {
  constexpr size_t kMax = std::numeric_limits<size_t>::max();
  size_t span = 0;
  if (count == 0) return offset;
  if (__builtin_mul_overflow(count - 1, stride, &span) || __builtin_add_overflow(span, offset, &span) ||
      __builtin_add_overflow(span, element_size, &span))
    return kMax;
  return span;
}

// Checks that `count` elements of `element_size` bytes, `stride` apart from `offset`,
// fit in `bytes`.
void check_fits(const GltfContext& ctx, const std::string& who, int view_index, const ByteRange& bytes,
                size_t offset, size_t count, size_t stride, size_t element_size) {
  const size_t needed = bytes_spanned(offset, count, stride, element_size);
  if (needed > bytes.size)
    ctx.fail(
        "{} reads past the end of bufferView {}: needs {} bytes (byteOffset {}, stride {}, count {}) "
        "but the view holds {}",
        who, view_index, needed, offset, stride, count, bytes.size);
}

uint32_t read_unsigned(const unsigned char* p, int component_type) {
  switch (component_type) {
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE:
      return *p;
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT: {
      uint16_t v;
      std::memcpy(&v, p, sizeof v);
      return v;
    }
    default: {
      uint32_t v;
      std::memcpy(&v, p, sizeof v);
      return v;
    }
  }
}

// An accessor whose dense part has been checked to lie inside its bufferView and buffer.
struct CheckedAccessor {
  const tinygltf::Accessor& accessor;
  std::string who;  // accessor_label()
  size_t component_size;
  size_t components;
  ByteRange dense;  // data == nullptr when the accessor has no bufferView (all zeros)
  size_t stride = 0;
  size_t element_size() const { return component_size * components; }
};

// Without a bufferView an accessor costs no file bytes, so its count is bounded here
// instead: a few bytes of JSON must not allocate gigabytes. 2^24 (16.7M) elements is as
// many vertices as the largest single meshes we know of; as VEC3 floats that is 200 MB,
// twice over once baked (at 2^26 a 300-byte file made the loader take over 2 GB).
constexpr size_t kMaxElementsWithoutBufferView = size_t{1} << 24;

CheckedAccessor check_accessor(const GltfContext& ctx, int index, const std::string& role) {
  if (!in_range(index, ctx.model.accessors.size()))
    ctx.fail("{} refers to accessor {}, which does not exist ({} accessors)", role, index,
             ctx.model.accessors.size());
  const tinygltf::Accessor& accessor = ctx.model.accessors[static_cast<size_t>(index)];
  CheckedAccessor checked{
      accessor, accessor_label(index, role), component_size(accessor.componentType), 0, {}, 0};
  const std::string& who = checked.who;
  if (checked.component_size == 0) ctx.fail("{} has invalid componentType {}", who, accessor.componentType);
  const int components = tinygltf::GetNumComponentsInType(static_cast<uint32_t>(accessor.type));
  if (components <= 0) ctx.fail("{} has an invalid type", who);
  checked.components = static_cast<size_t>(components);
  if (accessor.count == 0) ctx.fail("{} has count 0", who);
  if (accessor.bufferView < 0) {
    if (accessor.count > kMaxElementsWithoutBufferView)
      ctx.fail("{} has count {} but no bufferView", who, accessor.count);
    return checked;
  }
  checked.dense = view_bytes(ctx, accessor.bufferView, who);
  const size_t declared_stride = ctx.model.bufferViews[static_cast<size_t>(accessor.bufferView)].byteStride;
  if (declared_stride != 0 && declared_stride < checked.element_size())
    ctx.fail("{}: bufferView {} byteStride {} is smaller than one element ({} bytes)", who,
             accessor.bufferView, declared_stride, checked.element_size());
  checked.stride = declared_stride != 0 ? declared_stride : checked.element_size();
  check_fits(ctx, who, accessor.bufferView, checked.dense, accessor.byteOffset, accessor.count,
             checked.stride, checked.element_size());
  return checked;
}

void visit_sparse(const GltfContext& ctx, const tinygltf::Accessor& accessor, const std::string& who,
                  size_t element_size, const ElementVisitor& visit) {
  const auto& sparse = accessor.sparse;
  if (sparse.count < 1 || static_cast<size_t>(sparse.count) > accessor.count)
    ctx.fail("{} sparse count {} is outside [1, {}]", who, sparse.count, accessor.count);
  const size_t count = static_cast<size_t>(sparse.count);
  const int index_type = sparse.indices.componentType;
  if (index_type != TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE &&
      index_type != TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT &&
      index_type != TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT)
    ctx.fail("{} sparse indices have componentType {}, not an unsigned integer type", who, index_type);
  if (sparse.indices.byteOffset < 0 || sparse.values.byteOffset < 0)
    ctx.fail("{} sparse byteOffset is negative", who);
  const size_t index_size = component_size(index_type);
  const std::string index_who = who + " sparse indices";
  const std::string value_who = who + " sparse values";
  const ByteRange indices = view_bytes(ctx, sparse.indices.bufferView, index_who);
  const ByteRange values = view_bytes(ctx, sparse.values.bufferView, value_who);
  const size_t index_offset = static_cast<size_t>(sparse.indices.byteOffset);
  const size_t value_offset = static_cast<size_t>(sparse.values.byteOffset);
  // Sparse indices and values are tightly packed.
  check_fits(ctx, index_who, sparse.indices.bufferView, indices, index_offset, count, index_size, index_size);
  check_fits(ctx, value_who, sparse.values.bufferView, values, value_offset, count, element_size,
             element_size);
  for (size_t i = 0; i < count; ++i) {
    const uint32_t target = read_unsigned(indices.data + index_offset + i * index_size, index_type);
    if (target >= accessor.count)
      ctx.fail("{} sparse index {} (entry {}) is out of range for its {} elements", who, target, i,
               accessor.count);
    visit(target, values.data + value_offset + i * element_size);
  }
}

// Calls `visit` for each element: first the dense ones (zeros when the accessor has no
// bufferView), then the sparse substitutions, which overwrite them.
void visit_elements(const GltfContext& ctx, const CheckedAccessor& checked, const ElementVisitor& visit) {
  const tinygltf::Accessor& accessor = checked.accessor;
  if (checked.dense.data != nullptr) {
    const unsigned char* first = checked.dense.data + accessor.byteOffset;
    for (size_t i = 0; i < accessor.count; ++i) visit(i, first + i * checked.stride);
  } else {
    const std::vector<unsigned char> zeros(checked.element_size(), 0);
    for (size_t i = 0; i < accessor.count; ++i) visit(i, zeros.data());
  }
  if (accessor.sparse.isSparse) visit_sparse(ctx, accessor, checked.who, checked.element_size(), visit);
}

// Fails unless the accessor's type and component kind are ones `format` admits; warns
// when a quantized kind appears in a file that does not declare KHR_mesh_quantization.
void check_format(const GltfContext& ctx, const tinygltf::Accessor& accessor, const std::string& who,
                  const FloatFormat& format) {
  if (std::find(format.types.begin(), format.types.end(), accessor.type) == format.types.end()) {
    std::vector<std::string> expected;
    for (int type : format.types) expected.emplace_back(type_name(type));
    ctx.fail("{} has type {}, expected {}", who, type_name(accessor.type), fmt::join(expected, " or "));
  }
  const ComponentKind kind{accessor.componentType, accessor.normalized};
  const KindUse use = classify(format, kind);
  if (use == KindUse::refused) {
    std::vector<ComponentKind> expected = format.core;
    expected.insert(expected.end(), format.quantized.begin(), format.quantized.end());
    ctx.fail("{} has componentType {}{}, expected FLOAT{}{}", who, component_name(kind.component_type),
             kind.normalized ? " (normalized)" : "", expected.empty() ? "" : ", ", describe_kinds(expected));
  }
  const auto& used = ctx.model.extensionsUsed;
  if (use == KindUse::quantized && std::find(used.begin(), used.end(), "KHR_mesh_quantization") == used.end())
    ctx.warn(
        "{} has componentType {}{}, which needs KHR_mesh_quantization, not declared in extensionsUsed: "
        "read as that extension says",
        who, component_name(kind.component_type), kind.normalized ? " (normalized)" : "");
}

// Elements as floats through `visit_all`, which calls its argument for every element.
template <typename VisitAll>
FloatElements dequantize_elements(const GltfContext& ctx, const tinygltf::Accessor& accessor,
                                  const std::string& who, size_t components, VisitAll&& visit_all) {
  FloatElements out;
  out.count = accessor.count;
  out.components = static_cast<int>(components);
  out.values.resize(out.count * components);
  const size_t size = component_size(accessor.componentType);
  visit_all([&](size_t element, const unsigned char* p) {
    for (size_t c = 0; c < components; ++c)
      out.values[element * components + c] =
          dequantize(p + c * size, accessor.componentType, accessor.normalized);
  });
  for (size_t i = 0; i < out.values.size(); ++i) {
    if (!std::isfinite(out.values[i])) {
      const auto first = out.values.begin() + static_cast<std::ptrdiff_t>(i / components * components);
      ctx.fail("{} element {} is not finite: ({})", who, i / components,
               fmt::join(first, first + static_cast<std::ptrdiff_t>(components), ", "));
    }
  }
  return out;
}

const tinygltf::Accessor& find_accessor(const GltfContext& ctx, int index, const std::string& role) {
  if (!in_range(index, ctx.model.accessors.size()))
    ctx.fail("{} refers to accessor {}, which does not exist ({} accessors)", role, index,
             ctx.model.accessors.size());
  return ctx.model.accessors[static_cast<size_t>(index)];
}

}  // namespace

std::string accessor_label(int accessor, const std::string& role) {
  return fmt::format("accessor {} ({})", accessor, role);
}

ByteRange view_bytes(const GltfContext& ctx, int view_index, const std::string& who) {
  const auto& model = ctx.model;
  if (!in_range(view_index, model.bufferViews.size()))
    ctx.fail("{} refers to bufferView {}, which does not exist ({} bufferViews)", who, view_index,
             model.bufferViews.size());
  const tinygltf::BufferView& view = model.bufferViews[static_cast<size_t>(view_index)];
  if (!in_range(view.buffer, model.buffers.size()))
    ctx.fail("bufferView {} refers to buffer {}, which does not exist ({} buffers)", view_index, view.buffer,
             model.buffers.size());
  const std::vector<unsigned char>& data = model.buffers[static_cast<size_t>(view.buffer)].data;
  if (view.byteOffset > data.size() || view.byteLength > data.size() - view.byteOffset)
    ctx.fail("bufferView {} (byteOffset {}, byteLength {}) reads past the end of buffer {} ({} bytes)",
             view_index, view.byteOffset, view.byteLength, view.buffer, data.size());
  return {data.data() + view.byteOffset, view.byteLength};
}

FloatElements read_floats(const GltfContext& ctx, int index, const std::string& role,
                          const FloatFormat& format) {
  const CheckedAccessor checked = check_accessor(ctx, index, role);
  check_format(ctx, checked.accessor, checked.who, format);
  return dequantize_elements(ctx, checked.accessor, checked.who, checked.components,
                             [&](const ElementVisitor& visit) { visit_elements(ctx, checked, visit); });
}

const tinygltf::Accessor& check_float_accessor(const GltfContext& ctx, int index, const std::string& role,
                                               const FloatFormat& format) {
  const tinygltf::Accessor& accessor = find_accessor(ctx, index, role);
  const std::string who = accessor_label(index, role);
  if (component_size(accessor.componentType) == 0)
    ctx.fail("{} has invalid componentType {}", who, accessor.componentType);
  check_format(ctx, accessor, who, format);
  return accessor;
}

FloatElements floats_from_packed(const GltfContext& ctx, int index, const std::string& role,
                                 const std::vector<unsigned char>& packed) {
  const tinygltf::Accessor& accessor = find_accessor(ctx, index, role);
  const std::string who = accessor_label(index, role);
  const int components = tinygltf::GetNumComponentsInType(static_cast<uint32_t>(accessor.type));
  const size_t element_size =
      component_size(accessor.componentType) * static_cast<size_t>(std::max(components, 0));
  if (element_size == 0 || packed.size() % element_size != 0 ||
      packed.size() / element_size != accessor.count)
    ctx.fail("{}: {} bytes of decoded data do not make {} elements of {} bytes", who, packed.size(),
             accessor.count, element_size);
  return dequantize_elements(ctx, accessor, who, static_cast<size_t>(components),
                             [&](const ElementVisitor& visit) {
                               for (size_t i = 0; i < accessor.count; ++i)
                                 visit(i, packed.data() + i * element_size);
                             });
}

std::vector<uint32_t> read_indices(const GltfContext& ctx, int index, const std::string& role) {
  const CheckedAccessor checked = check_accessor(ctx, index, role);
  const tinygltf::Accessor& accessor = checked.accessor;
  const int type = accessor.componentType;
  if (accessor.type != TINYGLTF_TYPE_SCALAR)
    ctx.fail("{} has type {}, expected SCALAR", checked.who, type_name(accessor.type));
  if (type != TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE && type != TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT &&
      type != TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT)
    ctx.fail("{} has componentType {}, expected UNSIGNED_BYTE, UNSIGNED_SHORT or UNSIGNED_INT", checked.who,
             component_name(type));
  std::vector<uint32_t> indices(accessor.count);
  visit_elements(ctx, checked,
                 [&](size_t element, const unsigned char* p) { indices[element] = read_unsigned(p, type); });
  return indices;
}

}  // namespace phyir::scenes::gltf
