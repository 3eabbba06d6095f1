// Malformed compressed geometry: each broken Draco or meshopt file is refused with a
// phyir::Error that starts with the file and names the object; bytes flipped one at a
// time in the compressed data give an error or a load, never a crash.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <string>

#include "gltf_compression_helpers.h"
#include "phyir/core/error.h"
#include "phyir/scenes/gltf_loader.h"

namespace phyir::scenes {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;
using ::testing::HasSubstr;
using ::testing::StartsWith;

const fs::path kCompressed = fs::path(PHYIR_TEST_DATA_DIR) / "gltf" / "compressed";

// Writes `parts` and returns the loader's error message (empty if it loaded).
std::string load_error(const test::GlbParts& parts) {
  const fs::path path = test::write_glb(parts, test::fresh_test_dir(), "broken");
  try {
    load_gltf(path);
  } catch (const Error& e) {
    const std::string message = e.what();
    EXPECT_THAT(message, StartsWith(path.string() + ": "));
    return message;
  }
  ADD_FAILURE() << "loaded without an error";
  return {};
}

struct FlipOutcomes {
  int errors = 0, loads = 0;
};

// Loads `parts` once per byte of [start, start + length) of its BIN chunk, that byte inverted:
// each load must end in an error or a scene, never a crash.
FlipOutcomes flip_each_byte(const test::GlbParts& parts, size_t start, size_t length) {
  const fs::path dir = test::fresh_test_dir();
  FlipOutcomes outcomes;
  for (size_t i = start; i < start + length; ++i) {
    test::GlbParts flipped = parts;
    flipped.bin[i] ^= 0xFF;
    try {
      load_gltf(test::write_glb(flipped, dir, "flipped"));
      ++outcomes.loads;
    } catch (const Error&) {
      ++outcomes.errors;
    }
  }
  return outcomes;
}

// --- Draco (quad_draco.glb: bufferView 1 holds the Draco mesh, POSITION id 0) --------

class DracoErrors : public ::testing::Test {
 protected:
  test::GlbParts parts = test::read_glb(kCompressed / "quad_draco.glb");
  json& extension() {
    return parts.doc["meshes"][0]["primitives"][0]["extensions"]["KHR_draco_mesh_compression"];
  }
  json& draco_view() { return parts.doc["bufferViews"][1]; }
};

TEST_F(DracoErrors, BufferViewPastTheEndOfItsBuffer) {
  draco_view()["byteOffset"] = 200;  // 125 bytes from 200 in a 205-byte buffer
  const std::string message = load_error(parts);
  EXPECT_THAT(message, HasSubstr("bufferView"));
  EXPECT_THAT(message, HasSubstr("past the end of buffer 0"));
}

TEST_F(DracoErrors, BufferViewThatDoesNotExist) {
  extension()["bufferView"] = 9;
  EXPECT_THAT(load_error(parts), HasSubstr("bufferView 9"));
}

TEST_F(DracoErrors, TruncatedBytes) {
  draco_view()["byteLength"] = 60;
  const std::string message = load_error(parts);
  EXPECT_THAT(message, HasSubstr("mesh 0 'quad' primitive 0 KHR_draco_mesh_compression"));
  EXPECT_THAT(message, HasSubstr("Draco cannot decode bufferView 1 (60 bytes)"));
}

TEST_F(DracoErrors, GarbledHeader) {
  const size_t start = draco_view()["byteOffset"];
  for (size_t i = 0; i < 8; ++i) parts.bin[start + i] ^= 0x5A;
  EXPECT_THAT(load_error(parts), HasSubstr("Draco cannot decode bufferView 1"));
}

TEST_F(DracoErrors, AttributeIdNotInTheDecodedMesh) {
  extension()["attributes"]["POSITION"] = 7;
  EXPECT_THAT(load_error(parts),
              HasSubstr("attribute POSITION has id 7, which the decoded Draco mesh does not have"));
}

TEST_F(DracoErrors, AttributeThePrimitiveLacks) {
  extension()["attributes"]["NORMAL"] = 0;
  EXPECT_THAT(load_error(parts), HasSubstr("names attribute NORMAL, which the primitive does not have"));
}

TEST_F(DracoErrors, AccessorCountDisagreesWithTheDecodedPoints) {
  parts.doc["accessors"][1]["count"] = 5;
  EXPECT_THAT(load_error(parts),
              HasSubstr("accessor 1 (POSITION of mesh 0 'quad' primitive 0) has count 5 but the "
                        "decoded Draco mesh has 4 points"));
}

TEST_F(DracoErrors, IndexCountDisagreesWithTheDecodedFaces) {
  parts.doc["accessors"][0]["count"] = 9;
  EXPECT_THAT(load_error(parts), HasSubstr("has count 9 but the decoded Draco mesh has 2 triangles"));
}

TEST_F(DracoErrors, RequiredButThePrimitiveHasNoCompressedData) {
  parts.doc["meshes"][0]["primitives"][0].erase("extensions");
  EXPECT_THAT(load_error(parts),
              HasSubstr("mesh 0 'quad' primitive 0 has no KHR_draco_mesh_compression extension "
                        "and its POSITION accessor 1 has no bufferView"));
}

TEST_F(DracoErrors, EveryByteFlippedGivesAnErrorOrALoad) {
  const FlipOutcomes outcomes = flip_each_byte(parts, draco_view()["byteOffset"], draco_view()["byteLength"]);
  EXPECT_GT(outcomes.errors, 0);
  std::printf("[compression] Draco bytes flipped: %d errors, %d loads\n", outcomes.errors, outcomes.loads);
}

// --- meshopt (quad_meshopt.glb: bufferView 2 holds POSITION, 4 elements of 8 bytes) ----

class MeshoptErrors : public ::testing::Test {
 protected:
  test::GlbParts parts = test::read_glb(kCompressed / "quad_meshopt.glb");
  json& positions() { return parts.doc["bufferViews"][2]; }
  json& extension() { return positions()["extensions"]["EXT_meshopt_compression"]; }
};

TEST_F(MeshoptErrors, StrideNotAMultipleOfFour) {
  positions().erase("byteStride");  // optional on the parent; the extension's is required
  positions()["byteLength"] = 24;
  extension()["byteStride"] = 6;
  const std::string message = load_error(parts);
  EXPECT_THAT(message, HasSubstr("EXT_meshopt_compression"));
  EXPECT_THAT(message, HasSubstr("byteStride"));
  EXPECT_THAT(message, HasSubstr("6"));
}

TEST_F(MeshoptErrors, CountDisagreesWithTheView) {
  extension()["count"] = 5;
  EXPECT_THAT(load_error(parts),
              HasSubstr("bufferView 2 EXT_meshopt_compression: byteStride 8 times count 5 does not "
                        "equal the bufferView's byteLength 32"));
}

TEST_F(MeshoptErrors, TruncatedCompressedBytes) {
  extension()["byteLength"] = 40;
  EXPECT_THAT(load_error(parts),
              HasSubstr("bufferView 2 EXT_meshopt_compression: meshoptimizer cannot decode its 40 "
                        "bytes"));
}

TEST_F(MeshoptErrors, CompressedBytesPastTheEndOfTheirBuffer) {
  extension()["byteOffset"] = 200;
  EXPECT_THAT(load_error(parts), HasSubstr("reads past the end of buffer 0"));
}

TEST_F(MeshoptErrors, DeclaredSizeNoCodecCanReach) {
  // 60 compressed bytes cannot hold 2^20 elements: refused before anything is allocated.
  extension()["count"] = 1 << 20;
  positions()["byteLength"] = 8 << 20;
  parts.doc["buffers"][1]["byteLength"] = 9 << 20;
  parts.doc["accessors"][1]["count"] = 1 << 20;
  EXPECT_THAT(load_error(parts), HasSubstr("more than any meshopt codec expands to"));
}

TEST_F(MeshoptErrors, CompressedDataInTheFallbackBuffer) {
  extension()["buffer"] = 1;
  EXPECT_THAT(load_error(parts), HasSubstr("buffer 1"));
}

TEST_F(MeshoptErrors, RequiredButTheViewHasNoCompressedData) {
  positions().erase("extensions");
  EXPECT_THAT(load_error(parts),
              HasSubstr("bufferView 2 points into buffer 1, an EXT_meshopt_compression fallback "
                        "buffer, without the extension"));
}

TEST_F(MeshoptErrors, EveryByteFlippedGivesAnErrorOrALoad) {
  const FlipOutcomes outcomes = flip_each_byte(parts, extension()["byteOffset"], extension()["byteLength"]);
  EXPECT_GT(outcomes.errors + outcomes.loads, 0);
  std::printf("[compression] meshopt bytes flipped: %d errors, %d loads\n", outcomes.errors, outcomes.loads);
}

// A .gltf whose fallback buffer has no uri: the fallback is never looked for on disk.
TEST(MeshoptFallback, BufferWithoutUriInAGltfLoads) {
  const Scene scene = load_gltf(kCompressed / "room_meshopt_filters.gltf");
  EXPECT_FALSE(scene.meshes.empty());
}

}  // namespace
}  // namespace phyir::scenes
