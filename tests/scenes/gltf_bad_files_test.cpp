// Malformed files: each must throw phyir::Error naming the file and the exact object,
// never crash or read out of bounds.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <limits>

#include "gltf_test_helpers.h"
#include "phyir/core/atomic_file.h"
#include "phyir/core/error.h"
#include "phyir/scenes/gltf_loader.h"

namespace phyir::scenes {
namespace {

using nlohmann::json;
using test::GltfBuilder;
using ::testing::AllOf;
using ::testing::HasSubstr;

std::filesystem::path fixture(const std::string& name) {
  return std::filesystem::path(PHYIR_TEST_DATA_DIR) / "gltf" / name;
}

// The message of the phyir::Error that loading `path` throws ("" and a failure if none).
std::string load_error(const std::filesystem::path& path) {
  try {
    load_gltf(path);
  } catch (const Error& e) {
    return e.what();
  }
  ADD_FAILURE() << path << " loaded without an error";
  return "";
}

// A valid one-triangle file; tests break one thing in it before writing.
GltfBuilder triangle_builder() {
  GltfBuilder b;
  b.add_triangles("tri", test::unit_triangle(), {0, 1, 2});
  b.set_scene({b.add_node({{"mesh", 0}})});
  return b;
}

TEST(GltfBadFiles, TruncatedJson) {
  EXPECT_THAT(load_error(fixture("truncated.gltf")),
              AllOf(HasSubstr("truncated.gltf: invalid JSON"), HasSubstr("unexpected end of input")));
}

TEST(GltfBadFiles, MissingFile) {
  EXPECT_THAT(load_error(fixture("no_such_file.gltf")), HasSubstr("no_such_file.gltf: file not found"));
}

TEST(GltfBadFiles, MissingBin) {
  EXPECT_THAT(load_error(fixture("missing_bin.gltf")),
              HasSubstr("missing_bin.gltf: buffer 0 uri 'missing.bin' not found"));
}

TEST(GltfBadFiles, BinShorterThanItsByteLength) {
  GltfBuilder b = triangle_builder();
  const std::filesystem::path path = b.write_gltf(test::fresh_test_dir(), "short");
  std::filesystem::resize_file(path.parent_path() / "short.bin", 20);
  EXPECT_THAT(load_error(path),
              HasSubstr("short.gltf: buffer 0 uri 'short.bin' holds 20 bytes but its byteLength is"));
}

TEST(GltfBadFiles, AccessorReadsPastItsBufferView) {
  GltfBuilder b = triangle_builder();
  b.doc["accessors"][0]["count"] = 4;  // 4 VEC3 floats = 48 bytes from a 36-byte view
  EXPECT_THAT(load_error(b.write_gltf(test::fresh_test_dir(), "overrun")),
              AllOf(HasSubstr("overrun.gltf: accessor 0 (POSITION of mesh 0 'tri' primitive 0)"),
                    HasSubstr("reads past the end of bufferView 0: needs 48 bytes"), HasSubstr("holds 36")));
}

TEST(GltfBadFiles, BufferViewReadsPastItsBuffer) {
  GltfBuilder b = triangle_builder();
  b.doc["bufferViews"][0]["byteOffset"] = 40;
  EXPECT_THAT(load_error(b.write_gltf(test::fresh_test_dir(), "view")),
              AllOf(HasSubstr(
                  "view.gltf: bufferView 0 (byteOffset 40, byteLength 36) reads past the end of buffer 0")));
}

TEST(GltfBadFiles, HugeCountDoesNotOverflow) {
  GltfBuilder b = triangle_builder();
  b.doc["accessors"][0]["count"] = std::numeric_limits<uint64_t>::max() / 2;
  EXPECT_THAT(
      load_error(b.write_gltf(test::fresh_test_dir(), "huge")),
      HasSubstr(
          "huge.gltf: accessor 0 (POSITION of mesh 0 'tri' primitive 0) reads past the end of bufferView 0"));
}

TEST(GltfBadFiles, IndexOutOfRange) {
  GltfBuilder b;
  b.add_triangles("tri", test::unit_triangle(), {0, 1, 7});
  b.set_scene({b.add_node({{"mesh", 0}})});
  EXPECT_THAT(
      load_error(b.write_gltf(test::fresh_test_dir(), "index")),
      HasSubstr("index.gltf: index 7 (element 2 of accessor 1) is out of range for mesh 0 'tri' primitive 0 "
                "with 3 vertices"));
}

TEST(GltfBadFiles, NanPosition) {
  GltfBuilder b;
  b.add_triangles("tri", {{0, 0, 0}, {std::numeric_limits<float>::quiet_NaN(), 0, 0}, {0, 1, 0}}, {0, 1, 2});
  b.set_scene({b.add_node({{"mesh", 0}})});
  EXPECT_THAT(
      load_error(b.write_gltf(test::fresh_test_dir(), "nan")),
      HasSubstr("nan.gltf: accessor 0 (POSITION of mesh 0 'tri' primitive 0) element 1 is not finite"));
}

TEST(GltfBadFiles, InfinitePositionInGlb) {
  GltfBuilder b;
  b.add_triangles("tri", {{0, 0, 0}, {1, 0, 0}, {0, std::numeric_limits<float>::infinity(), 0}}, {});
  b.set_scene({b.add_node({{"mesh", 0}})});
  EXPECT_THAT(
      load_error(b.write_glb(test::fresh_test_dir(), "inf")),
      HasSubstr("inf.glb: accessor 0 (POSITION of mesh 0 'tri' primitive 0) element 2 is not finite"));
}

TEST(GltfBadFiles, UnknownRequiredExtension) {
  EXPECT_THAT(
      load_error(fixture("unknown_required_extension.gltf")),
      HasSubstr(
          "unknown_required_extension.gltf: required extension EXT_phyir_from_the_future is not supported"));
}

TEST(GltfBadFiles, MissingTextureImage) {
  EXPECT_THAT(load_error(fixture("missing_texture.gltf")),
              AllOf(HasSubstr("missing_texture.gltf: image 0 uri 'textures/absent.png' not found"),
                    HasSubstr((fixture("textures") / "absent.png").string())));
}

TEST(GltfBadFiles, WrongAccessorTypeForAttribute) {
  GltfBuilder b = triangle_builder();
  b.doc["meshes"][0]["primitives"][0]["attributes"]["NORMAL"] =
      b.add_floats(std::vector<glm::vec2>(3, {0, 1}));
  EXPECT_THAT(
      load_error(b.write_gltf(test::fresh_test_dir(), "type")),
      HasSubstr("type.gltf: accessor 2 (NORMAL of mesh 0 'tri' primitive 0) has type VEC2, expected VEC3"));
}

TEST(GltfBadFiles, AttributeCountDiffersFromPositions) {
  GltfBuilder b = triangle_builder();
  b.doc["meshes"][0]["primitives"][0]["attributes"]["NORMAL"] =
      b.add_floats(std::vector<glm::vec3>(2, {0, 0, 1}));
  EXPECT_THAT(load_error(b.write_gltf(test::fresh_test_dir(), "count")),
              HasSubstr("count.gltf: mesh 0 'tri' primitive 0 attribute NORMAL (accessor 2) has 2 elements "
                        "but POSITION has 3"));
}

TEST(GltfBadFiles, SparseIndexOutOfRange) {
  GltfBuilder b = triangle_builder();
  const std::vector<uint16_t> index{9};
  const glm::vec3 value(1.0f);
  b.doc["accessors"][0]["sparse"] = {
      {"count", 1},
      {"indices", {{"bufferView", b.add_view(index.data(), 2)}, {"componentType", 5123}}},
      {"values", {{"bufferView", b.add_view(&value, 12)}}}};
  EXPECT_THAT(load_error(b.write_gltf(test::fresh_test_dir(), "sparse")),
              HasSubstr("sparse.gltf: accessor 0 (POSITION of mesh 0 'tri' primitive 0) sparse index 9 "
                        "(entry 0) is out of range"));
}

TEST(GltfBadFiles, MissingReferencedObjects) {
  const std::filesystem::path dir = test::fresh_test_dir();
  GltfBuilder b = triangle_builder();
  b.doc["nodes"][0]["mesh"] = 3;
  EXPECT_THAT(load_error(b.write_gltf(dir, "mesh")),
              HasSubstr("mesh.gltf: node 0 refers to mesh 3, which does not exist"));
  b = triangle_builder();
  b.doc["meshes"][0]["primitives"][0]["material"] = 2;
  EXPECT_THAT(
      load_error(b.write_gltf(dir, "material")),
      HasSubstr("material.gltf: mesh 0 'tri' primitive 0 refers to material 2, which does not exist"));
  b = triangle_builder();
  b.doc["meshes"][0]["primitives"][0]["attributes"]["POSITION"] = 5;
  EXPECT_THAT(
      load_error(b.write_gltf(dir, "accessor")),
      HasSubstr(
          "accessor.gltf: POSITION of mesh 0 'tri' primitive 0 refers to accessor 5, which does not exist"));
}

TEST(GltfBadFiles, NodeCycle) {
  GltfBuilder b = triangle_builder();
  b.add_node({{"children", {0}}});
  b.doc["nodes"][0]["children"] = {1};
  EXPECT_THAT(load_error(b.write_gltf(test::fresh_test_dir(), "cycle")),
              HasSubstr("cycle.gltf: node 0 is reached twice"));
}

TEST(GltfBadFiles, TruncatedGlb) {
  GltfBuilder b = triangle_builder();
  const std::filesystem::path path = b.write_glb(test::fresh_test_dir(), "cut");
  std::filesystem::resize_file(path, std::filesystem::file_size(path) - 8);
  EXPECT_THAT(load_error(path), HasSubstr("cut.glb: GLB header declares"));
}

// Every prefix of a valid GLB (and of its .gltf JSON) must load or throw phyir::Error:
// no crash, no other exception type.
TEST(GltfBadFiles, EveryTruncationIsAnErrorNotACrash) {
  GltfBuilder b = triangle_builder();
  b.doc["meshes"][0]["primitives"][0]["attributes"]["NORMAL"] =
      b.add_floats(std::vector<glm::vec3>(3, {0, 0, 1}));
  const std::filesystem::path dir = test::fresh_test_dir();
  const std::string glb = read_file(b.write_glb(dir, "whole"));
  const std::string gltf = read_file(b.write_gltf(dir, "whole"));
  for (const auto& [name, bytes] : {std::make_pair("cut.glb", glb), std::make_pair("cut.gltf", gltf)}) {
    for (size_t length = 0; length < bytes.size(); ++length) {
      test::write_bytes(dir / name, bytes.data(), length);
      try {
        load_gltf(dir / name);
      } catch (const Error& e) {
        EXPECT_THAT(e.what(), HasSubstr(name)) << "length " << length;
      }
    }
  }
}

}  // namespace
}  // namespace phyir::scenes
