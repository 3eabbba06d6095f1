// KHR_mesh_quantization's dequantization rules, component type by component type, on
// one-triangle files: normalized signed integers max(c / (2^(n-1) - 1), -1), normalized
// unsigned c / (2^n - 1), others their value (with the node transform that scales them),
// and the component types each attribute refuses.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cstring>
#include <map>

#include "gltf_test_helpers.h"
#include "phyir/core/error.h"
#include "phyir/scenes/gltf_loader.h"

namespace phyir::scenes {
namespace {

using nlohmann::json;
using ::testing::HasSubstr;

constexpr int kByte = 5120, kUnsignedByte = 5121, kShort = 5122, kUnsignedShort = 5123, kUnsignedInt = 5125;

// An attribute of 3 elements of `components` values each, stored as `component_type`,
// each element padded to 4 bytes as glTF requires of vertex attributes.
struct Attribute {
  int component_type;
  bool normalized;
  std::vector<int64_t> values;
  int components = 3;
};

int add_attribute(test::GltfBuilder& b, const Attribute& a) {
  static const char* kTypes[] = {"", "SCALAR", "VEC2", "VEC3", "VEC4"};
  const size_t size = a.component_type == kByte || a.component_type == kUnsignedByte ? 1
                      : a.component_type == kUnsignedInt                             ? 4
                                                                                     : 2;
  const size_t stride = (size * static_cast<size_t>(a.components) + 3) / 4 * 4;
  const size_t count = a.values.size() / static_cast<size_t>(a.components);
  std::vector<unsigned char> bytes(count * stride, 0);
  for (size_t i = 0; i < a.values.size(); ++i) {
    const size_t at =
        i / static_cast<size_t>(a.components) * stride + i % static_cast<size_t>(a.components) * size;
    std::memcpy(bytes.data() + at, &a.values[i], size);  // little-endian: the low bytes
  }
  const int view = b.add_view(bytes.data(), bytes.size(), stride);
  return b.add_accessor({{"bufferView", view},
                         {"componentType", a.component_type},
                         {"normalized", a.normalized},
                         {"count", count},
                         {"type", kTypes[a.components]}});
}

// One triangle: POSITION (and the other attributes given) under `node`.
Scene load_triangle(const Attribute& position, const std::map<std::string, Attribute>& others = {},
                    json node = json::object(), bool declare_extension = true) {
  test::GltfBuilder b;
  json attributes = {{"POSITION", add_attribute(b, position)}};
  for (const auto& [name, attribute] : others) attributes[name] = add_attribute(b, attribute);
  b.add_mesh("tri", {{{"attributes", attributes}}});
  node["mesh"] = 0;
  b.set_scene({b.add_node(node)});
  if (declare_extension) {
    b.doc["extensionsUsed"] = {"KHR_mesh_quantization"};
    b.doc["extensionsRequired"] = {"KHR_mesh_quantization"};
  }
  return load_gltf(b.write_gltf(test::fresh_test_dir(), "quantized"));
}

std::string load_error(const Attribute& position, const std::map<std::string, Attribute>& others = {}) {
  try {
    load_triangle(position, others);
  } catch (const Error& e) {
    return e.what();
  }
  ADD_FAILURE() << "loaded without an error";
  return {};
}

// The three positions of the triangle (vertices are unshared for flat normals, in order).
std::vector<glm::vec3> positions_of(const Scene& scene) {
  const Mesh& mesh = scene.meshes.at(0);
  const glm::uvec3 t = mesh.triangles.at(0);
  return {mesh.positions[t.x], mesh.positions[t.y], mesh.positions[t.z]};
}

const std::vector<glm::vec3> kUnitTriangle = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}};

TEST(Dequantization, NormalizedSignedByte) {
  // -128 and -127 both give -1 (spec: max(c / 127, -1)); 127 gives 1.
  const auto p = positions_of(load_triangle({kByte, true, {-128, -127, 127, 127, 0, 64, 0, 1, -1}}));
  EXPECT_EQ(p[0], glm::vec3(-1.0f, -1.0f, 1.0f));
  EXPECT_EQ(p[1], glm::vec3(1.0f, 0.0f, 64.0f / 127.0f));
  EXPECT_EQ(p[2], glm::vec3(0.0f, 1.0f / 127.0f, -1.0f / 127.0f));
}

TEST(Dequantization, NormalizedUnsignedByte) {
  const auto p = positions_of(load_triangle({kUnsignedByte, true, {0, 255, 128, 255, 0, 0, 0, 255, 1}}));
  EXPECT_EQ(p[0], glm::vec3(0.0f, 1.0f, 128.0f / 255.0f));
  EXPECT_EQ(p[2], glm::vec3(0.0f, 1.0f, 1.0f / 255.0f));
}

TEST(Dequantization, NormalizedSignedShort) {
  const auto p =
      positions_of(load_triangle({kShort, true, {-32768, -32767, 32767, 32767, 0, 0, 0, 16384, 0}}));
  EXPECT_EQ(p[0], glm::vec3(-1.0f, -1.0f, 1.0f));
  EXPECT_EQ(p[2], glm::vec3(0.0f, 16384.0f / 32767.0f, 0.0f));
}

TEST(Dequantization, NormalizedUnsignedShort) {
  const auto p = positions_of(load_triangle({kUnsignedShort, true, {0, 0, 0, 65535, 0, 0, 0, 32768, 0}}));
  EXPECT_EQ(p[1], glm::vec3(1.0f, 0.0f, 0.0f));
  EXPECT_EQ(p[2], glm::vec3(0.0f, 32768.0f / 65535.0f, 0.0f));
}

TEST(Dequantization, IntegerPositionsScaledByTheirNode) {
  // What a quantizer writes: integer positions, and the node scale and offset that undo it.
  const Scene scene = load_triangle({kShort, false, {0, 0, 0, 1000, 0, 0, 0, -1000, 0}}, {},
                                    {{"scale", {0.001, 0.001, 0.001}}, {"translation", {1, 2, 3}}});
  const auto p = positions_of(scene);
  EXPECT_EQ(p[0], glm::vec3(1, 2, 3));
  EXPECT_NEAR(p[1].x, 2.0f, 1e-6f);
  EXPECT_NEAR(p[2].y, 1.0f, 1e-6f);
}

TEST(Dequantization, IntegerPositionsOfEveryType) {
  for (int type : {kByte, kUnsignedByte, kShort, kUnsignedShort}) {
    SCOPED_TRACE(type);
    const bool is_signed = type == kByte || type == kShort;
    const int64_t big = type == kByte ? 127 : type == kUnsignedByte ? 255 : type == kShort ? 32767 : 65535;
    const auto p =
        positions_of(load_triangle({type, false, {0, 0, 0, big, 0, 0, 0, is_signed ? -big : 1, 0}}));
    EXPECT_EQ(p[1].x, static_cast<float>(big));
    EXPECT_EQ(p[2].y, is_signed ? -static_cast<float>(big) : 1.0f);
  }
}

TEST(Dequantization, NormalsAndTangentsAsNormalizedSignedIntegers) {
  const Scene scene = load_triangle(
      {kShort, false, {0, 0, 0, 1, 0, 0, 0, 1, 0}},
      {{"NORMAL", {kByte, true, {0, 0, 127, 0, 0, 127, 0, -128, 0}}},
       {"TANGENT", {kShort, true, {32767, 0, 0, -32767, 32767, 0, 0, 32767, 0, 0, 32767, 32767}, 4}}});
  const Mesh& mesh = scene.meshes.at(0);
  EXPECT_EQ(mesh.normals[0], glm::vec3(0, 0, 1));
  EXPECT_EQ(mesh.normals[2], glm::vec3(0, -1, 0));
  EXPECT_EQ(mesh.tangents[0], glm::vec4(1, 0, 0, -1));
  EXPECT_EQ(mesh.tangents[2], glm::vec4(0, 0, 1, 1));
}

TEST(Dequantization, TexcoordsOfEveryKind) {
  const Attribute position{kShort, false, {0, 0, 0, 1, 0, 0, 0, 1, 0}};
  const Scene scene =
      load_triangle(position, {{"TEXCOORD_0", {kByte, false, {-2, 3, 0, 0, 127, -128}, 2}},
                               {"TEXCOORD_1", {kShort, true, {-32768, 32767, 0, 0, 0, 0}, 2}}});
  const Mesh& mesh = scene.meshes.at(0);
  EXPECT_EQ(mesh.texcoords0[0], glm::vec2(-2, 3));
  EXPECT_EQ(mesh.texcoords0[2], glm::vec2(127, -128));
  EXPECT_EQ(mesh.texcoords1[0], glm::vec2(-1, 1));
}

TEST(Dequantization, KindsTheAttributesRefuse) {
  const Attribute position{kShort, false, {0, 0, 0, 1, 0, 0, 0, 1, 0}};
  EXPECT_THAT(
      load_error(position, {{"NORMAL", {kUnsignedByte, true, {0, 0, 255, 0, 0, 255, 0, 0, 255}}}}),
      HasSubstr("(NORMAL of mesh 0 'tri' primitive 0) has componentType UNSIGNED_BYTE (normalized), expected "
                "FLOAT, BYTE (normalized), SHORT (normalized)"));
  EXPECT_THAT(load_error(position, {{"NORMAL", {kByte, false, {0, 0, 1, 0, 0, 1, 0, 0, 1}}}}),
              HasSubstr("has componentType BYTE, expected FLOAT"));
  EXPECT_THAT(load_error(position, {{"COLOR_0", {kShort, true, {0, 0, 1, 0, 0, 1, 0, 0, 1}}}}),
              HasSubstr("(COLOR_0 of mesh 0 'tri' primitive 0) has componentType SHORT (normalized)"));
  EXPECT_THAT(load_error({kUnsignedInt, false, {0, 0, 0, 1, 0, 0, 0, 1, 0}}),
              HasSubstr("(POSITION of mesh 0 'tri' primitive 0) has componentType UNSIGNED_INT"));
}

TEST(Dequantization, UndeclaredExtensionLoadsWithAWarning) {
  const Scene scene =
      load_triangle({kShort, true, {0, 0, 0, 32767, 0, 0, 0, 32767, 0}}, {}, json::object(), false);
  EXPECT_EQ(positions_of(scene)[1], glm::vec3(1, 0, 0));
  bool warned = false;
  for (const std::string& w : scene.warnings)
    warned |= w.find("needs KHR_mesh_quantization") != std::string::npos;
  EXPECT_TRUE(warned);
}

}  // namespace
}  // namespace phyir::scenes
