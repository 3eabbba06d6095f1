#include "gltf/compression/gltf_meshopt.h"

#include <meshoptimizer.h>

#include <optional>
#include <string>
#include <vector>

#include "gltf/read/gltf_values.h"

namespace phyir::scenes::gltf {

namespace {

constexpr char kExtension[] = "EXT_meshopt_compression";

// No codec of the extension expands its input more than 64 times: the attribute codec
// spends at least 2 header bits on a group of 16 bytes (triangles: 1 byte per triangle of
// up to 12 bytes; indices: 1 byte per index of up to 4). A view declaring more is an error
// before anything is allocated, so a few bytes of JSON cannot ask for gigabytes.
constexpr uint64_t kMaxExpansion = 64;

enum class Mode { attributes, triangles, indices };
enum class Filter { none, octahedral, quaternion, exponential };

// The extension object of one bufferView, every member checked for type and sign.
struct CompressedView {
  int buffer = -1;
  size_t byte_offset = 0;
  size_t byte_length = 0;
  size_t byte_stride = 0;
  size_t count = 0;
  Mode mode = Mode::attributes;
  Filter filter = Filter::none;
};

const tinygltf::Value* find_extension(const tinygltf::ExtensionMap& extensions) {
  const auto it = extensions.find(kExtension);
  return it != extensions.end() ? &it->second : nullptr;
}

size_t unsigned_member(const Diagnostics& d, const tinygltf::Value& object, const char* key,
                       const std::string& where, std::optional<int> fallback) {
  const std::optional<int> value = integer_member(d, object, key, where);
  if (!value && !fallback) d.fail("{} has no {}", where, key);
  const int v = value.value_or(fallback.value_or(0));
  if (v < 0) d.fail("{} {} is negative ({})", where, key, v);
  return static_cast<size_t>(v);
}

std::string string_member(const Diagnostics& d, const tinygltf::Value& object, const char* key,
                          const std::string& where, const char* fallback) {
  const tinygltf::Value* value = member(object, key);
  if (value == nullptr) {
    if (fallback == nullptr) d.fail("{} has no {}", where, key);
    return fallback;
  }
  if (!value->IsString()) d.fail("{} {} is not a string", where, key);
  return value->Get<std::string>();
}

Mode parse_mode(const Diagnostics& d, const std::string& mode, const std::string& where) {
  if (mode == "ATTRIBUTES") return Mode::attributes;
  if (mode == "TRIANGLES") return Mode::triangles;
  if (mode == "INDICES") return Mode::indices;
  d.fail("{} mode '{}' is not ATTRIBUTES, TRIANGLES or INDICES", where, mode);
}

Filter parse_filter(const Diagnostics& d, const std::string& filter, const std::string& where) {
  if (filter == "NONE") return Filter::none;
  if (filter == "OCTAHEDRAL") return Filter::octahedral;
  if (filter == "QUATERNION") return Filter::quaternion;
  if (filter == "EXPONENTIAL") return Filter::exponential;
  d.fail("{} filter '{}' is not NONE, OCTAHEDRAL, QUATERNION or EXPONENTIAL", where, filter);
}

CompressedView parse_extension(const Diagnostics& d, const tinygltf::Value& ext, const std::string& where) {
  if (!ext.IsObject()) d.fail("{} is not a JSON object", where);
  CompressedView view;
  const std::optional<int> buffer = integer_member(d, ext, "buffer", where);
  if (!buffer) d.fail("{} has no buffer", where);
  view.buffer = *buffer;
  view.byte_offset = unsigned_member(d, ext, "byteOffset", where, 0);
  view.byte_length = unsigned_member(d, ext, "byteLength", where, std::nullopt);
  view.byte_stride = unsigned_member(d, ext, "byteStride", where, std::nullopt);
  view.count = unsigned_member(d, ext, "count", where, std::nullopt);
  view.mode = parse_mode(d, string_member(d, ext, "mode", where, nullptr), where);
  view.filter = parse_filter(d, string_member(d, ext, "filter", where, "NONE"), where);
  return view;
}

// The rules of the extension's "For the extension object to be valid" list.
void check_layout(const Diagnostics& d, const CompressedView& c, const tinygltf::BufferView& parent,
                  const std::string& where) {
  const size_t stride = c.byte_stride;
  if (c.count == 0) d.fail("{} count is 0", where);
  if (parent.byteStride != 0 && parent.byteStride != stride)
    d.fail("{} byteStride {} differs from the bufferView's byteStride {}", where, stride, parent.byteStride);
  size_t decoded = 0;
  if (__builtin_mul_overflow(stride, c.count, &decoded) || decoded != parent.byteLength)
    d.fail("{}: byteStride {} times count {} does not equal the bufferView's byteLength {}", where, stride,
           c.count, parent.byteLength);
  if (c.mode == Mode::attributes && (stride == 0 || stride % 4 != 0 || stride > 256))
    d.fail("{} byteStride {} is not a multiple of 4 in [4, 256] (mode ATTRIBUTES)", where, stride);
  if (c.mode != Mode::attributes && stride != 2 && stride != 4)
    d.fail("{} byteStride {} is not 2 or 4 (index modes)", where, stride);
  if (c.mode == Mode::triangles && c.count % 3 != 0)
    d.fail("{} count {} is not a multiple of 3 (mode TRIANGLES)", where, c.count);
  if (c.mode != Mode::attributes && c.filter != Filter::none)
    d.fail("{} has a filter, which only mode ATTRIBUTES may have", where);
  if (c.filter == Filter::octahedral && stride != 4 && stride != 8)
    d.fail("{} byteStride {} is not 4 or 8 (filter OCTAHEDRAL)", where, stride);
  if (c.filter == Filter::quaternion && stride != 8)
    d.fail("{} byteStride {} is not 8 (filter QUATERNION)", where, stride);
  // EXPONENTIAL: stride % 4 == 0 holds already (mode ATTRIBUTES).
}

class ViewDecoder {
 public:
  ViewDecoder(tinygltf::Model& model, const Diagnostics& diagnostics) : model_(model), d_(diagnostics) {
    for (const tinygltf::Buffer& buffer : model.buffers) budget_ += buffer.data.size() * kMaxExpansion;
  }

  void decode(int view_index, const tinygltf::Value& ext) {
    const std::string where = fmt::format("bufferView {} {}", view_index, kExtension);
    tinygltf::BufferView& view = model_.bufferViews[static_cast<size_t>(view_index)];
    const CompressedView c = parse_extension(d_, ext, where);
    check_layout(d_, c, view, where);
    const std::vector<unsigned char>& source = compressed_buffer(c, where);
    if (c.byte_offset > source.size() || c.byte_length > source.size() - c.byte_offset)
      d_.fail("{} (byteOffset {}, byteLength {}) reads past the end of buffer {} ({} bytes)", where,
              c.byte_offset, c.byte_length, c.buffer, source.size());
    const size_t decoded_size = view.byteLength;
    if (decoded_size > c.byte_length * kMaxExpansion || decoded_size > budget_)
      d_.fail("{} decodes {} bytes from {}: more than any meshopt codec expands to", where, decoded_size,
              c.byte_length);
    budget_ -= decoded_size;

    tinygltf::Buffer decoded;
    decoded.name = fmt::format("bufferView {} decoded", view_index);
    decoded.data.resize(decoded_size);
    const int status = run_codec(c, source.data() + c.byte_offset, decoded.data.data());
    if (status != 0)
      d_.fail("{}: meshoptimizer cannot decode its {} bytes ({})", where, c.byte_length, codec_error(status));
    apply_filter(c, decoded.data.data());
    model_.buffers.push_back(std::move(decoded));
    view.buffer = static_cast<int>(model_.buffers.size()) - 1;
    view.byteOffset = 0;
  }

 private:
  const std::vector<unsigned char>& compressed_buffer(const CompressedView& c,
                                                      const std::string& where) const {
    if (!in_range(c.buffer, model_.buffers.size()))
      d_.fail("{} refers to buffer {}, which does not exist ({} buffers)", where, c.buffer,
              model_.buffers.size());
    const tinygltf::Buffer& buffer = model_.buffers[static_cast<size_t>(c.buffer)];
    if (is_meshopt_fallback(buffer))
      d_.fail("{} reads its compressed data from buffer {}, a fallback buffer", where, c.buffer);
    return buffer.data;
  }

  static int run_codec(const CompressedView& c, const unsigned char* source, unsigned char* out) {
    switch (c.mode) {
      case Mode::attributes:
        return meshopt_decodeVertexBuffer(out, c.count, c.byte_stride, source, c.byte_length);
      case Mode::triangles:
        return meshopt_decodeIndexBuffer(out, c.count, c.byte_stride, source, c.byte_length);
      default:
        return meshopt_decodeIndexSequence(out, c.count, c.byte_stride, source, c.byte_length);
    }
  }

  static const char* codec_error(int status) {
    switch (status) {
      case -1:
        return "unsupported encoding version";
      case -2:
        return "the data is truncated or malformed";
      case -3:
        return "bytes are left over after the last element";
      default:
        return "decoder error";
    }
  }

  static void apply_filter(const CompressedView& c, unsigned char* data) {
    switch (c.filter) {
      case Filter::octahedral:
        meshopt_decodeFilterOct(data, c.count, c.byte_stride);
        break;
      case Filter::quaternion:
        meshopt_decodeFilterQuat(data, c.count, c.byte_stride);
        break;
      case Filter::exponential:
        meshopt_decodeFilterExp(data, c.count, c.byte_stride);
        break;
      case Filter::none:
        break;
    }
  }

  tinygltf::Model& model_;
  const Diagnostics& d_;
  uint64_t budget_ = 0;  // bytes all views together may still decode to
};

// A view without the extension in a fallback buffer would read data that is not there.
void check_no_fallback_reads(const tinygltf::Model& model, const Diagnostics& d) {
  for (size_t i = 0; i < model.bufferViews.size(); ++i) {
    const int buffer = model.bufferViews[i].buffer;
    if (in_range(buffer, model.buffers.size()) &&
        is_meshopt_fallback(model.buffers[static_cast<size_t>(buffer)]))
      d.fail(
          "bufferView {} points into buffer {}, an {} fallback buffer, without the extension that says how "
          "to decode it",
          i, buffer, kExtension);
  }
}

}  // namespace

bool is_meshopt_fallback(const tinygltf::Buffer& buffer) {
  const tinygltf::Value* ext = find_extension(buffer.extensions);
  const tinygltf::Value* fallback = ext != nullptr ? member(*ext, "fallback") : nullptr;
  return fallback != nullptr && fallback->IsBool() && fallback->Get<bool>();
}

void decode_meshopt_views(tinygltf::Model& model, const Diagnostics& diagnostics) {
  // Fallback data is never read: a placeholder's byte (gltf_tinygltf_input.h) or, when
  // the file has real fallback data, bytes the compressed views replace.
  for (tinygltf::Buffer& buffer : model.buffers)
    if (is_meshopt_fallback(buffer)) std::vector<unsigned char>().swap(buffer.data);
  ViewDecoder decoder(model, diagnostics);
  for (size_t i = 0; i < model.bufferViews.size(); ++i) {
    const tinygltf::Value* ext = find_extension(model.bufferViews[i].extensions);
    if (ext != nullptr) decoder.decode(static_cast<int>(i), *ext);
  }
  check_no_fallback_reads(model, diagnostics);
}

}  // namespace phyir::scenes::gltf
