// The ten Khronos sample files in shared/testdata/khronos load with exactly the reference
// counts of that folder's README, and their baked normals agree with their geometry.
#include <gtest/gtest.h>

#include <filesystem>
#include <ostream>

#include "phyir/scenes/gltf_loader.h"

namespace phyir::scenes {
namespace {

struct KhronosCounts {
  const char* file;
  int default_scene, nodes, meshes, primitives, mesh_instances;
  size_t triangles;
  int materials, textures, images, samplers, cameras;
};

std::ostream& operator<<(std::ostream& os, const KhronosCounts& c) { return os << c.file; }

// The README's "Reference counts" table, column for column.
const KhronosCounts kReference[] = {
    {"Triangle.gltf", 0, 1, 1, 1, 1, 1, 0, 0, 0, 0, 0},
    {"TriangleWithoutIndices.gltf", 0, 1, 1, 1, 1, 1, 0, 0, 0, 0, 0},
    {"SimpleSparseAccessor.gltf", 0, 1, 1, 1, 1, 12, 0, 0, 0, 0, 0},
    {"SimpleMeshes.gltf", 0, 2, 1, 1, 2, 2, 0, 0, 0, 0, 0},
    {"Cameras.gltf", 0, 3, 1, 1, 1, 2, 0, 0, 0, 0, 2},
    {"MultipleScenes.gltf", 1, 2, 2, 2, 1, 2, 0, 0, 0, 0, 0},
    {"BoxVertexColors.gltf", 0, 1, 1, 1, 1, 12, 0, 0, 0, 0, 0},
    {"BoxTextured.gltf", 0, 3, 1, 1, 1, 12, 1, 1, 1, 1, 0},
    {"TextureCoordinateTest.gltf", 0, 6, 5, 5, 5, 10, 5, 1, 1, 1, 0},
    {"OrientationTest.gltf", 0, 13, 13, 13, 13, 524, 7, 0, 0, 0, 0},
};

std::filesystem::path khronos(const std::string& file) {
  return std::filesystem::path(PHYIR_SHARED_DIR) / "testdata" / "khronos" / file;
}

class KhronosSample : public ::testing::TestWithParam<KhronosCounts> {};

TEST_P(KhronosSample, LoadsWithTheReadmeCounts) {
  const KhronosCounts& ref = GetParam();
  const Scene scene = load_gltf(khronos(ref.file));
  const SourceInfo& info = scene.info;
  EXPECT_EQ(info.default_scene, ref.default_scene);
  EXPECT_EQ(info.nodes, ref.nodes);
  EXPECT_EQ(info.meshes, ref.meshes);
  EXPECT_EQ(info.primitives, ref.primitives);
  EXPECT_EQ(info.mesh_instances, ref.mesh_instances);
  EXPECT_EQ(scene.triangle_count(), ref.triangles);
  EXPECT_EQ(info.materials, ref.materials);
  EXPECT_EQ(info.textures, ref.textures);
  EXPECT_EQ(info.images, ref.images);
  EXPECT_EQ(info.samplers, ref.samplers);
  EXPECT_EQ(info.cameras, ref.cameras);
  // Every primitive here is TRIANGLES, so each instanced primitive is one baked mesh.
  EXPECT_EQ(scene.meshes.size(), static_cast<size_t>(ref.mesh_instances));
  // The file's materials, plus the default one when some primitive has none.
  EXPECT_GE(scene.materials.size(), static_cast<size_t>(ref.materials));
  EXPECT_LE(scene.materials.size(), static_cast<size_t>(ref.materials) + 1);
  EXPECT_FALSE(scene.bounds.empty());
}

// README: "In every triangle, the vertex normals agree with the geometric face normal"
// (minimum dot product 0.993). Baking must keep that, whatever the node transforms.
TEST_P(KhronosSample, BakedNormalsAgreeWithWinding) {
  const Scene scene = load_gltf(khronos(GetParam().file));
  for (const Mesh& mesh : scene.meshes) {
    ASSERT_EQ(mesh.normals.size(), mesh.positions.size()) << mesh.name;
    for (const glm::uvec3& t : mesh.triangles) {
      const glm::vec3 face = glm::normalize(
          glm::cross(mesh.positions[t.y] - mesh.positions[t.x], mesh.positions[t.z] - mesh.positions[t.x]));
      for (int k = 0; k < 3; ++k) ASSERT_GT(glm::dot(face, mesh.normals[t[k]]), 0.99f) << mesh.name;
    }
  }
}

INSTANTIATE_TEST_SUITE_P(Readme, KhronosSample, ::testing::ValuesIn(kReference),
                         [](const ::testing::TestParamInfo<KhronosCounts>& info) {
                           std::string name = info.param.file;
                           return name.substr(0, name.find('.'));
                         });

TEST(KhronosFeatures, CamerasFilePerspectiveAndOrthographic) {
  const Scene scene = load_gltf(khronos("Cameras.gltf"));
  ASSERT_EQ(scene.cameras.size(), 2u);
  int perspective = 0;
  for (const Camera& c : scene.cameras) {
    if (!c.perspective) continue;
    ++perspective;
    EXPECT_FLOAT_EQ(c.yfov, 0.7f);  // README: yfov 0.7, aspectRatio 1
    EXPECT_FLOAT_EQ(c.aspect_ratio, 1.0f);
  }
  EXPECT_EQ(perspective, 1);
  EXPECT_FALSE(scene.warnings.empty());  // the orthographic one
}

TEST(KhronosFeatures, BoxTexturedDecodesItsNonPowerOfTwoTexture) {
  const Scene scene = load_gltf(khronos("BoxTextured.gltf"));
  ASSERT_EQ(scene.textures.size(), 1u);
  EXPECT_EQ(scene.textures[0].width(), 211);  // README: 211x211 PNG, wrap REPEAT
  EXPECT_EQ(scene.textures[0].height(), 211);
  EXPECT_EQ(scene.textures[0].wrap_s, WrapMode::Repeat);
  EXPECT_EQ(scene.textures[0].encoding, TextureEncoding::SrgbColour);
  EXPECT_EQ(scene.meshes[0].texcoords0.size(), scene.meshes[0].positions.size());
}

TEST(KhronosFeatures, BoxVertexColorsAreRgb) {
  const Scene scene = load_gltf(khronos("BoxVertexColors.gltf"));
  const Mesh& mesh = scene.meshes[0];
  ASSERT_EQ(mesh.colors.size(), mesh.positions.size());
  for (const glm::vec4& c : mesh.colors) EXPECT_EQ(c.w, 1.0f);  // VEC3 colours are opaque
}

}  // namespace
}  // namespace phyir::scenes
