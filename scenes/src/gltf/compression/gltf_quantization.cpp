#include "gltf/compression/gltf_quantization.h"

#include <fmt/format.h>
#include <fmt/ranges.h>

#include <algorithm>
#include <cstdint>
#include <cstring>

#include "gltf/read/gltf_tinygltf.h"

namespace phyir::scenes::gltf {

namespace {

constexpr int kByte = TINYGLTF_COMPONENT_TYPE_BYTE;
constexpr int kUnsignedByte = TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE;
constexpr int kShort = TINYGLTF_COMPONENT_TYPE_SHORT;
constexpr int kUnsignedShort = TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT;

// BYTE, UNSIGNED_BYTE, SHORT, UNSIGNED_SHORT, normalized or not.
std::vector<ComponentKind> any_small_integer() {
  std::vector<ComponentKind> kinds;
  for (int type : {kByte, kUnsignedByte, kShort, kUnsignedShort})
    for (bool normalized : {true, false}) kinds.push_back({type, normalized});
  return kinds;
}

const std::vector<ComponentKind> kNormalizedSigned = {{kByte, true}, {kShort, true}};
const std::vector<ComponentKind> kNormalizedUnsigned = {{kUnsignedByte, true}, {kUnsignedShort, true}};

bool contains(const std::vector<ComponentKind>& kinds, const ComponentKind& kind) {
  return std::any_of(kinds.begin(), kinds.end(), [&](const ComponentKind& k) {
    return k.component_type == kind.component_type && k.normalized == kind.normalized;
  });
}

template <typename T>
T load(const unsigned char* p) {
  T value;  // glTF is little-endian, as are the machines we run on
  std::memcpy(&value, p, sizeof value);
  return value;
}

}  // namespace

FloatFormat attribute_format(const std::string& name) {
  // KHR_mesh_quantization, "Extending Mesh Attributes".
  if (name == "POSITION") return {{TINYGLTF_TYPE_VEC3}, {}, any_small_integer()};
  if (name == "NORMAL") return {{TINYGLTF_TYPE_VEC3}, {}, kNormalizedSigned};
  if (name == "TANGENT") return {{TINYGLTF_TYPE_VEC4}, {}, kNormalizedSigned};
  if (name.rfind("TEXCOORD_", 0) == 0) {
    std::vector<ComponentKind> quantized;
    for (const ComponentKind& kind : any_small_integer())
      if (!contains(kNormalizedUnsigned, kind)) quantized.push_back(kind);
    return {{TINYGLTF_TYPE_VEC2}, kNormalizedUnsigned, quantized};
  }
  if (name.rfind("COLOR_", 0) == 0)
    return {{TINYGLTF_TYPE_VEC3, TINYGLTF_TYPE_VEC4}, kNormalizedUnsigned, {}};
  return {};
}

KindUse classify(const FloatFormat& format, const ComponentKind& kind) {
  if (kind.component_type == TINYGLTF_COMPONENT_TYPE_FLOAT) return KindUse::float_data;
  if (contains(format.core, kind)) return KindUse::core;
  if (contains(format.quantized, kind)) return KindUse::quantized;
  return KindUse::refused;
}

float dequantize(const unsigned char* p, int component_type, bool normalized) {
  switch (component_type) {
    case TINYGLTF_COMPONENT_TYPE_FLOAT:
      return load<float>(p);
    case kByte: {
      const float c = load<int8_t>(p);
      return normalized ? std::max(c / 127.0f, -1.0f) : c;
    }
    case kUnsignedByte: {
      const float c = load<uint8_t>(p);
      return normalized ? c / 255.0f : c;
    }
    case kShort: {
      const float c = load<int16_t>(p);
      return normalized ? std::max(c / 32767.0f, -1.0f) : c;
    }
    case kUnsignedShort: {
      const float c = load<uint16_t>(p);
      return normalized ? c / 65535.0f : c;
    }
    default:  // UNSIGNED_INT: no vertex attribute admits it (attribute_format)
      return static_cast<float>(load<uint32_t>(p));
  }
}

size_t component_size(int component_type) {
  switch (component_type) {
    case kByte:
    case kUnsignedByte:
      return 1;
    case kShort:
    case kUnsignedShort:
      return 2;
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT:
    case TINYGLTF_COMPONENT_TYPE_FLOAT:
      return 4;
    default:
      return 0;  // INT and DOUBLE are not valid glTF 2.0 accessor types
  }
}

const char* component_name(int component_type) {
  switch (component_type) {
    case kByte:
      return "BYTE";
    case kUnsignedByte:
      return "UNSIGNED_BYTE";
    case kShort:
      return "SHORT";
    case kUnsignedShort:
      return "UNSIGNED_SHORT";
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT:
      return "UNSIGNED_INT";
    case TINYGLTF_COMPONENT_TYPE_FLOAT:
      return "FLOAT";
    default:
      return "invalid";
  }
}

std::string describe_kinds(const std::vector<ComponentKind>& kinds) {
  std::vector<std::string> names;
  for (const ComponentKind& kind : kinds)
    names.push_back(
        fmt::format("{}{}", component_name(kind.component_type), kind.normalized ? " (normalized)" : ""));
  return fmt::format("{}", fmt::join(names, ", "));
}

}  // namespace phyir::scenes::gltf
