// Compressed and quantized geometry: the variants in tests/data/gltf/compressed (made by
// gltf-transform, see its README) load to the same triangles as their originals, within
// the tolerance of their quantization; meshopt filters and modes gltf-transform does not
// write, on files built here with meshoptimizer's encoder; compressed data preferred over
// a fallback.
#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <meshoptimizer.h>

#include <cmath>
#include <cstdio>
#include <map>

#include "gltf_compression_helpers.h"
#include "gltf_test_helpers.h"
#include "phyir/scenes/gltf_loader.h"

namespace phyir::scenes {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;

const fs::path kCompressed = fs::path(PHYIR_TEST_DATA_DIR) / "gltf" / "compressed";  // variants are relative to it

// A variant and what its quantization allows. Positions: the grid spans the mesh's
// bounding box, so a coordinate is off by at most half a step, box size / 2^bits (signed
// normalized storage keeps bits - 1 for each half of the box; Draco uses all bits over
// the box). UVs likewise: range / 2^bits, the range at least [0, 1]. Normals and
// tangents: an angle.
struct Variant {
  const char* file;
  const char* original;
  int position_bits;
  int uv_bits;
  float normal_degrees;
  float uv_divisor = 1.0f;  // non-normalized texcoords: the stored integer range
};

std::ostream& operator<<(std::ostream& os, const Variant& v) { return os << v.file; }

// 10-bit normals (Draco's default and gltf-transform's) are within 0.2 degrees; 8-bit ones
// (gltf-transform's octahedral filter, --quantize-normal 8) within 0.7 (measured: see the
// test's output). The bounds below leave a factor of about 2.
const Variant kVariants[] = {
    {"room_draco.glb", "room.glb", 14, 12, 0.5f},
    {"room_draco_sequential.glb", "room.glb", 14, 12, 0.5f},
    {"room_meshopt.glb", "room.glb", 14, 12, 0.5f},
    {"room_meshopt_filters.gltf", "room.glb", 14, 12, 1.5f},
    {"room_quantized.glb", "room.glb", 14, 12, 0.5f},
    {"room_quantized_unnormalized.glb", "room.glb", 14, 12, 0.5f, 65535.0f},
    {"room_quantized_8bit.glb", "room.glb", 8, 8, 1.5f},
    {"room_quantized_8bit_unnormalized.glb", "room.glb", 8, 8, 1.5f, 255.0f},
    {"quad_draco.glb", "../textured_quad.gltf", 14, 12, 0.0f},
    {"quad_meshopt.glb", "../textured_quad.gltf", 14, 12, 0.0f},
    {"quad_quantized.glb", "../textured_quad.gltf", 14, 12, 0.0f},
    {"quad_quantized_unnormalized.glb", "../textured_quad.gltf", 14, 12, 0.0f, 65535.0f},
    // Blender's export of tests/data/gltf/blender_lit_room and scripts/gltf_variants.sh's variants.
    {"../blender_lit_room/variants/draco.gltf", "../blender_lit_room/lit_room.gltf", 14, 12, 0.5f},
    {"../blender_lit_room/variants/meshopt.gltf", "../blender_lit_room/lit_room.gltf", 14, 12, 1.5f},
    {"../blender_lit_room/variants/quantize.gltf", "../blender_lit_room/lit_room.gltf", 14, 12, 0.5f},
};

// Meshes by name and, for a mesh that several nodes place, by occurrence ("chair/0#2"):
// variants keep the node order.
std::map<std::string, const Mesh*> by_name(const Scene& scene) {
  std::map<std::string, const Mesh*> meshes;
  std::map<std::string, int> seen;
  for (const Mesh& mesh : scene.meshes) meshes[mesh.name + "#" + std::to_string(seen[mesh.name]++)] = &mesh;
  return meshes;
}

// Largest extent of the UVs: quantizers fit their grid to it (gltf-transform to [0, 1]).
float uv_range(const Mesh& mesh) {
  glm::vec2 lo(0.0f), hi(1.0f);
  for (const glm::vec2& uv : mesh.texcoords0) {
    lo = glm::min(lo, uv);
    hi = glm::max(hi, uv);
  }
  return std::max(hi.x - lo.x, hi.y - lo.y);
}

size_t triangle_count(const Scene& scene) {
  size_t n = 0;
  for (const Mesh& mesh : scene.meshes) n += mesh.triangles.size();
  return n;
}

class CompressedVariant : public ::testing::TestWithParam<Variant> {};

TEST_P(CompressedVariant, LoadsTheSameTrianglesAsItsOriginal) {
  const Variant& v = GetParam();
  const Scene original = load_gltf(kCompressed / v.original);
  const Scene variant = load_gltf(kCompressed / v.file);
  ASSERT_EQ(triangle_count(variant), triangle_count(original));
  const auto originals = by_name(original);
  const auto variants = by_name(variant);
  ASSERT_EQ(variants.size(), originals.size());
  test::MeshDifference worst;
  float worst_position_ratio = 0.0f;  // error / tolerance
  for (const auto& [name, variant_mesh] : variants) {
    SCOPED_TRACE(name);
    ASSERT_EQ(originals.count(name), 1u);
    const Mesh& mesh = *variant_mesh;
    const Mesh& reference = *originals.at(name);
    const float tolerance = test::bounding_box_size(reference) / std::ldexp(1.0f, v.position_bits) + 1e-6f;
    const test::MeshDifference d = test::compare_meshes(reference, mesh, tolerance, v.uv_divisor);
    EXPECT_EQ(d.unmatched, 0u);
    EXPECT_EQ(d.triangles, reference.triangles.size());
    EXPECT_LE(d.normal_degrees, v.normal_degrees);
    EXPECT_LE(d.tangent_degrees, v.normal_degrees);
    EXPECT_EQ(d.tangent_sign_flips, 0);
    EXPECT_LE(d.uv, uv_range(reference) / std::ldexp(1.0f, v.uv_bits));
    EXPECT_EQ(mesh.tangents.empty(), reference.tangents.empty());
    worst_position_ratio = std::max(worst_position_ratio, d.position / tolerance);
    worst.position = std::max(worst.position, d.position);
    worst.normal_degrees = std::max(worst.normal_degrees, d.normal_degrees);
    worst.tangent_degrees = std::max(worst.tangent_degrees, d.tangent_degrees);
    worst.uv = std::max(worst.uv, d.uv);
  }
  std::printf(
      "[compression] %-43s %4zu triangles: position %.2g (%.2f of tolerance), normal %.3f deg, "
      "tangent %.3f deg, uv %.2g\n",
      v.file, triangle_count(variant), worst.position, worst_position_ratio, worst.normal_degrees,
      worst.tangent_degrees, worst.uv);
}

INSTANTIATE_TEST_SUITE_P(Gltf, CompressedVariant, ::testing::ValuesIn(kVariants));

TEST(CompressedVariants, RequiredExtensionsLoadWithoutFallbackWarnings) {
  for (const char* file : {"room_draco.glb", "room_meshopt.glb", "room_quantized.glb"}) {
    SCOPED_TRACE(file);
    const Scene scene = load_gltf(kCompressed / file);
    EXPECT_FALSE(scene.info.extensions_required.empty());
    for (const std::string& w : scene.warnings)
      EXPECT_THAT(w, ::testing::Not(::testing::HasSubstr("ignored")));
  }
}

TEST(CompressedVariants, UnnormalizedTexcoordsKeepTheirTextureTransform) {
  const Scene scene = load_gltf(kCompressed / "quad_quantized_unnormalized.glb");
  ASSERT_EQ(scene.materials.size(), 1u);
  const glm::vec2 scale = scene.materials[0].base_color_texture.transform.scale;
  EXPECT_NEAR(scale.x, 1.0f / 65535.0f, 1e-9f);
  EXPECT_NEAR(scale.y, 1.0f / 65535.0f, 1e-9f);
}

// --- Compressed data preferred over a fallback that has data -------------------------

// quad_meshopt.glb with its fallback buffer given data (zeros) and the extension only used.
TEST(CompressedPreference, MeshoptIsDecodedEvenWhenTheFallbackHasData) {
  test::GlbParts parts = test::read_glb(kCompressed / "quad_meshopt.glb");
  json& fallback = parts.doc["buffers"][1];
  const size_t size = fallback["byteLength"];
  ASSERT_EQ(size % 3, 0u);
  fallback["uri"] = "data:application/octet-stream;base64," + std::string(size / 3 * 4, 'A');
  parts.doc["extensionsRequired"] = json::array({"KHR_mesh_quantization"});
  const Scene scene = load_gltf(test::write_glb(parts, test::fresh_test_dir(), "used_only"));
  const Scene original = load_gltf(kCompressed / "quad_quantized.glb");
  ASSERT_EQ(scene.meshes.size(), 1u);
  const test::MeshDifference d = test::compare_meshes(original.meshes[0], scene.meshes[0], 1e-6f);
  EXPECT_EQ(d.triangles, 2u);
  EXPECT_EQ(d.unmatched, 0u);
}

// quad_draco.glb with uncompressed accessors that hold zeros and the extension only used.
TEST(CompressedPreference, DracoIsDecodedEvenWhenAccessorsHaveData) {
  test::GlbParts parts = test::read_glb(kCompressed / "quad_draco.glb");
  const size_t zeros_offset = parts.bin.size();
  parts.bin.resize(zeros_offset + 64, 0);
  parts.doc["buffers"][0]["byteLength"] = parts.bin.size();
  parts.doc["bufferViews"].push_back({{"buffer", 0}, {"byteOffset", zeros_offset}, {"byteLength", 64}});
  const int zeros = static_cast<int>(parts.doc["bufferViews"].size()) - 1;
  for (json& accessor : parts.doc["accessors"]) accessor["bufferView"] = zeros;
  parts.doc.erase("extensionsRequired");
  const Scene scene = load_gltf(test::write_glb(parts, test::fresh_test_dir(), "used_only"));
  const Scene original = load_gltf(kCompressed / "../textured_quad.gltf");
  ASSERT_EQ(scene.meshes.size(), 1u);
  const test::MeshDifference d = test::compare_meshes(original.meshes[0], scene.meshes[0], 1e-4f);
  EXPECT_EQ(d.triangles, 2u);
  EXPECT_EQ(d.unmatched, 0u);
}

// --- meshopt modes and filters on files built here -------------------------------------

// One triangle list over `count` vertices whose attribute bytes are meshopt-encoded.
class MeshoptBuilder {
 public:
  test::GltfBuilder b;

  MeshoptBuilder() {
    b.doc["extensionsUsed"] = {"EXT_meshopt_compression", "KHR_mesh_quantization"};
    b.doc["extensionsRequired"] = {"EXT_meshopt_compression", "KHR_mesh_quantization"};
  }

  // Appends the encoded bytes to the BIN chunk and a fallback-buffer view decoding to
  // `raw` (count elements of `stride` bytes); returns the view.
  int add_encoded(const std::vector<unsigned char>& raw, size_t count, size_t stride, const std::string& mode,
                  const std::string& filter = "NONE") {
    std::vector<unsigned char> encoded = encode(raw, count, stride, mode);
    while (b.bin.size() % 4 != 0) b.bin.push_back(0);
    const size_t offset = b.bin.size();
    b.bin.insert(b.bin.end(), encoded.begin(), encoded.end());
    json view = {{"buffer", 1},
                 {"byteOffset", fallback_size_},
                 {"byteLength", raw.size()},
                 {"extensions",
                  {{"EXT_meshopt_compression",
                    {{"buffer", 0},
                     {"byteOffset", offset},
                     {"byteLength", encoded.size()},
                     {"byteStride", stride},
                     {"count", count},
                     {"mode", mode},
                     {"filter", filter}}}}}};
    if (mode == "ATTRIBUTES") view["byteStride"] = stride;
    fallback_size_ += (raw.size() + 3) / 4 * 4;
    b.doc["bufferViews"].push_back(view);
    return static_cast<int>(b.doc["bufferViews"].size()) - 1;
  }

  fs::path write(const std::string& name) {
    test::GlbParts parts{b.doc, b.bin};
    parts.doc["buffers"] =
        json::array({{{"byteLength", b.bin.size()}},
                     {{"byteLength", fallback_size_},
                      {"extensions", {{"EXT_meshopt_compression", {{"fallback", true}}}}}}});
    b.set_scene({b.add_node({{"mesh", 0}})});
    parts.doc["scenes"] = b.doc["scenes"];
    parts.doc["scene"] = 0;
    parts.doc["nodes"] = b.doc["nodes"];
    return test::write_glb(parts, test::fresh_test_dir(), name);
  }

 private:
  static std::vector<unsigned char> encode(const std::vector<unsigned char>& raw, size_t count, size_t stride,
                                           const std::string& mode) {
    std::vector<unsigned char> out;
    if (mode == "ATTRIBUTES") {
      out.resize(meshopt_encodeVertexBufferBound(count, stride));
      out.resize(meshopt_encodeVertexBuffer(out.data(), out.size(), raw.data(), count, stride));
      return out;
    }
    std::vector<unsigned int> indices(count);
    for (size_t i = 0; i < count; ++i)
      indices[i] = stride == 2 ? reinterpret_cast<const uint16_t*>(raw.data())[i]
                               : reinterpret_cast<const uint32_t*>(raw.data())[i];
    if (mode == "TRIANGLES") {
      out.resize(meshopt_encodeIndexBufferBound(count, count));
      out.resize(meshopt_encodeIndexBuffer(out.data(), out.size(), indices.data(), count));
    } else {
      out.resize(meshopt_encodeIndexSequenceBound(count, count));
      out.resize(meshopt_encodeIndexSequence(out.data(), out.size(), indices.data(), count));
    }
    return out;
  }

  size_t fallback_size_ = 0;
};

template <typename T>
std::vector<unsigned char> bytes_of(const std::vector<T>& values) {
  std::vector<unsigned char> out(values.size() * sizeof(T));
  std::memcpy(out.data(), values.data(), out.size());
  return out;
}

// Positions through the EXPONENTIAL filter (15-bit mantissa), normals through
// OCTAHEDRAL in 8-byte elements, tangents through QUATERNION (any unit 4-vector
// round-trips), indices in INDICES mode with 4-byte indices.
TEST(MeshoptFilters, ExponentialOctahedralQuaternionAndIndexSequence) {
  const std::vector<glm::vec3> positions = {{0.0f, 0.0f, 0.0f}, {1.5f, -0.25f, 3.0f}, {-2.0f, 7.0f, 0.125f}};
  const std::vector<glm::vec4> normals = {{0, 0, 1, 1},
                                          glm::vec4(glm::normalize(glm::vec3(1, 2, 3)), 1),
                                          glm::vec4(glm::normalize(glm::vec3(-1, 0.5f, -2)), 1)};
  const std::vector<glm::vec4> quaternions = {glm::normalize(glm::vec4(1, 2, 3, 4)),
                                              glm::normalize(glm::vec4(0.1f, 0.2f, 0.3f, 1)),
                                              glm::normalize(glm::vec4(-1, 0.5f, 0.25f, 2))};
  std::vector<uint32_t> exp(positions.size() * 3), oct(normals.size() * 2), quat(quaternions.size() * 2);
  meshopt_encodeFilterExp(exp.data(), positions.size(), 12, 15, &positions[0].x);
  meshopt_encodeFilterOct(oct.data(), normals.size(), 8, 16, &normals[0].x);
  meshopt_encodeFilterQuat(quat.data(), quaternions.size(), 8, 16, &quaternions[0].x);

  MeshoptBuilder m;
  const int p = m.add_encoded(bytes_of(exp), 3, 12, "ATTRIBUTES", "EXPONENTIAL");
  const int n = m.add_encoded(bytes_of(oct), 3, 8, "ATTRIBUTES", "OCTAHEDRAL");
  const int t = m.add_encoded(bytes_of(quat), 3, 8, "ATTRIBUTES", "QUATERNION");
  const int i = m.add_encoded(bytes_of(std::vector<uint32_t>{0, 1, 2}), 3, 4, "INDICES");
  m.b.add_accessor({{"bufferView", p}, {"componentType", 5126}, {"count", 3}, {"type", "VEC3"}});
  m.b.add_accessor(
      {{"bufferView", n}, {"componentType", 5122}, {"normalized", true}, {"count", 3}, {"type", "VEC3"}});
  m.b.add_accessor(
      {{"bufferView", t}, {"componentType", 5122}, {"normalized", true}, {"count", 3}, {"type", "VEC4"}});
  m.b.add_accessor({{"bufferView", i}, {"componentType", 5125}, {"count", 3}, {"type", "SCALAR"}});
  m.b.add_mesh("filtered",
               {{{"attributes", {{"POSITION", 0}, {"NORMAL", 1}, {"TANGENT", 2}}}, {"indices", 3}}});
  const Scene scene = load_gltf(m.write("filters"));

  ASSERT_EQ(scene.meshes.size(), 1u);
  const Mesh& mesh = scene.meshes[0];
  ASSERT_EQ(mesh.triangles.size(), 1u);
  EXPECT_EQ(mesh.triangles[0], glm::uvec3(0, 1, 2));
  for (size_t k = 0; k < 3; ++k) {
    SCOPED_TRACE(k);
    // 15-bit mantissa shared by the element: 2^-15 of its largest component (7 here).
    EXPECT_LE(test::max_abs(mesh.positions[k] - positions[k]), 8.0f * std::ldexp(1.0f, -15));
    EXPECT_LE(test::degrees_between(mesh.normals[k], glm::vec3(normals[k])), 0.01f);
    // The tangent is the quaternion's xyz (renormalised) and w, up to the sign of q.
    const glm::vec4 q = quaternions[k] *
                        (glm::dot(glm::vec3(mesh.tangents[k]), glm::vec3(quaternions[k])) < 0 ? -1.0f : 1.0f);
    EXPECT_LE(test::degrees_between(glm::vec3(mesh.tangents[k]), glm::vec3(q)), 0.05f);
    EXPECT_NEAR(mesh.tangents[k].w, q.w, 1e-3f);
  }
}

// TRIANGLES mode with 2-byte indices over a quad: the index codec keeps the triangles.
TEST(MeshoptFilters, TriangleCodecWithShortIndices) {
  const std::vector<glm::vec3> positions = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}};
  MeshoptBuilder m;
  const int p = m.add_encoded(bytes_of(positions), 4, 12, "ATTRIBUTES");
  const int i = m.add_encoded(bytes_of(std::vector<uint16_t>{0, 1, 2, 0, 2, 3}), 6, 2, "TRIANGLES");
  m.b.add_accessor({{"bufferView", p}, {"componentType", 5126}, {"count", 4}, {"type", "VEC3"}});
  m.b.add_accessor({{"bufferView", i}, {"componentType", 5123}, {"count", 6}, {"type", "SCALAR"}});
  m.b.add_mesh("quad", {{{"attributes", {{"POSITION", 0}}}, {"indices", 1}}});
  const Scene scene = load_gltf(m.write("triangles"));
  ASSERT_EQ(scene.meshes.size(), 1u);
  Mesh reference;  // the codec may rotate a triangle's corners, never change its winding
  reference.positions = positions;
  reference.normals.assign(4, glm::vec3(0, 0, 1));
  reference.triangles = {{0, 1, 2}, {0, 2, 3}};
  const test::MeshDifference d = test::compare_meshes(reference, scene.meshes[0], 1e-6f);
  EXPECT_EQ(d.triangles, 2u);
  EXPECT_EQ(d.unmatched, 0u);
  EXPECT_EQ(d.normal_degrees, 0.0f);
}

}  // namespace
}  // namespace phyir::scenes
