// EXT_mesh_gpu_instancing: gltf-transform's instanced file bakes to the triangles of the
// file it came from; node and instance transforms compose (world * T * R * S); a mirroring
// instance flips its winding; malformed instancing is refused naming the node.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <vector>

#include "gltf_test_helpers.h"
#include "phyir/core/error.h"
#include "phyir/scenes/gltf_loader.h"
#include "phyir/scenes/scene_info.h"

namespace phyir::scenes {
namespace {

using nlohmann::json;
using test::GltfBuilder;
using ::testing::AllOf;
using ::testing::HasSubstr;

constexpr float kTol = 1e-5f;

std::filesystem::path data(const std::string& file) {
  return std::filesystem::path(PHYIR_TEST_DATA_DIR) / "gltf" / "instancing" / file;
}

// One baked triangle: its corners in winding order and their normals.
struct WorldTriangle {
  glm::vec3 p[3];
  glm::vec3 n[3];
};

std::vector<WorldTriangle> world_triangles(const Scene& scene) {
  std::vector<WorldTriangle> out;
  for (const Mesh& mesh : scene.meshes)
    for (const glm::uvec3& t : mesh.triangles) {
      WorldTriangle w;
      for (int k = 0; k < 3; ++k) {
        w.p[k] = mesh.positions[t[k]];
        w.n[k] = mesh.normals[t[k]];
      }
      out.push_back(w);
    }
  return out;
}

bool near(const glm::vec3& a, const glm::vec3& b, float tol) { return glm::all(glm::lessThan(glm::abs(a - b), glm::vec3(tol))); }

// The same triangle: corners and normals equal up to a cyclic shift (same winding).
bool same_triangle(const WorldTriangle& a, const WorldTriangle& b, float tol) {
  for (int shift = 0; shift < 3; ++shift) {
    bool all = true;
    for (int k = 0; k < 3 && all; ++k)
      all = near(a.p[k], b.p[(k + shift) % 3], tol) && near(a.n[k], b.n[(k + shift) % 3], tol);
    if (all) return true;
  }
  return false;
}

glm::vec3 geometric_normal(const WorldTriangle& t) {
  return glm::normalize(glm::cross(t.p[1] - t.p[0], t.p[2] - t.p[0]));
}

// Every triangle of `expected` drawn once in `actual`, corners and normals within `tol`.
void expect_same_world_triangles(const Scene& expected_scene, const Scene& actual_scene, float tol) {
  const std::vector<WorldTriangle> expected = world_triangles(expected_scene);
  const std::vector<WorldTriangle> actual = world_triangles(actual_scene);
  ASSERT_EQ(actual.size(), expected.size());
  std::vector<bool> matched(actual.size(), false);
  size_t missing = 0;
  for (const WorldTriangle& e : expected) {
    bool found = false;
    for (size_t i = 0; i < actual.size() && !found; ++i)
      if (!matched[i] && same_triangle(e, actual[i], tol)) matched[i] = found = true;
    if (!found) ++missing;
  }
  EXPECT_EQ(missing, 0u) << "of " << expected.size() << " triangles";
}

void expect_near(const glm::vec3& actual, const glm::vec3& expected) {
  EXPECT_NEAR(actual.x, expected.x, kTol);
  EXPECT_NEAR(actual.y, expected.y, kTol);
  EXPECT_NEAR(actual.z, expected.z, kTol);
}

std::string load_error(const std::filesystem::path& path) {
  try {
    load_gltf(path);
  } catch (const Error& e) {
    return e.what();
  }
  return "(loaded)";
}

bool any_warning_has(const Scene& scene, const std::string& text) {
  for (const std::string& w : scene.warnings)
    if (w.find(text) != std::string::npos) return true;
  return false;
}

// The unit triangle (normals +Z) drawn by node 0 'batch' with `attributes` as its
// instancing. Accessors 0-2 are the mesh's.
class InstancedTriangle {
 public:
  InstancedTriangle() {
    builder.add_triangles("tri", test::unit_triangle(), {0, 1, 2}, {{0, 0, 1}, {0, 0, 1}, {0, 0, 1}});
  }

  template <typename Vec>
  int add(const std::vector<Vec>& values) {
    return builder.add_floats(values);
  }

  std::filesystem::path write(const json& attributes) {
    json node = {{"name", "batch"}, {"mesh", 0}};
    node["extensions"]["EXT_mesh_gpu_instancing"] = {{"attributes", attributes}};
    builder.doc["extensionsUsed"] = {"EXT_mesh_gpu_instancing"};
    builder.set_scene({builder.add_node(node)});
    return builder.write_gltf(test::fresh_test_dir(), "instanced");
  }

  GltfBuilder builder;
};

TEST(GltfInstancing, InstancedFileBakesToTheOriginalTriangles) {
  // shared_mesh.gltf: five nodes share a tetrahedron under a rotated, scaled parent, one of
  // them mirrored; gltf-transform instance made them one node with five instances.
  const Scene original = load_gltf(data("shared_mesh.gltf"));
  const Scene instanced = load_gltf(data("shared_mesh_instanced.glb"));
  ASSERT_EQ(original.triangle_count(), 20u);
  expect_same_world_triangles(original, instanced, 1e-4f);
  // Flat-shaded tetrahedra: every corner's normal is its face's, mirrored copy included.
  for (const WorldTriangle& t : world_triangles(instanced))
    for (int k = 0; k < 3; ++k) EXPECT_GT(glm::dot(geometric_normal(t), t.n[k]), 0.9999f);
  EXPECT_EQ(instanced.meshes.size(), 1u);
  EXPECT_EQ(original.meshes.size(), 5u);
  EXPECT_TRUE(instanced.warnings.empty()) << instanced.warnings.front();
}

TEST(GltfInstancing, BlenderRoomInstancedByGltfTransformBakesToTheSameTriangles) {
  // blender_lit_room (its README): Blender 3.4's export, and gltf-transform's variant that
  // draws the four chairs as one node's instances (TRANSLATION and ROTATION).
  const std::filesystem::path room = std::filesystem::path(PHYIR_TEST_DATA_DIR) / "gltf" / "blender_lit_room";
  const Scene original = load_gltf(room / "lit_room.gltf", LoadOptions{false});
  const Scene instanced = load_gltf(room / "variants" / "instance.gltf", LoadOptions{false});
  EXPECT_EQ(instanced.info.gpu_instances, 4);
  EXPECT_EQ(instanced.triangle_count(), 5314u);
  expect_same_world_triangles(original, instanced, 1e-4f);
}

TEST(GltfInstancing, SourceInfoCountsInstancesAndUniqueTriangles) {
  const Scene instanced = load_gltf(data("shared_mesh_instanced.glb"));
  EXPECT_EQ(instanced.info.mesh_instances, 1);
  EXPECT_EQ(instanced.info.gpu_instances, 5);
  EXPECT_EQ(instanced.info.unique_triangles, 4u);
  EXPECT_EQ(instanced.triangle_count(), 20u);
  const Scene original = load_gltf(data("shared_mesh.gltf"));
  EXPECT_EQ(original.info.gpu_instances, 0);
  EXPECT_EQ(original.info.unique_triangles, 4u);  // one primitive, drawn by five nodes
  const json info = scene_info_json(instanced);
  EXPECT_EQ(info["source_info"]["gpu_instances"], 5);
  EXPECT_EQ(info["source_info"]["unique_triangles"], 4);
  EXPECT_EQ(info["triangles"], 20);
  EXPECT_THAT(scene_info_text(instanced), HasSubstr("GPU instances: 5"));
}

TEST(GltfInstancing, NodeWorldTransformComposesWithInstanceTrs) {
  InstancedTriangle t;
  const float s = std::sqrt(0.5f);
  const int translation = t.add(std::vector<glm::vec3>{{1, 0, 0}, {0, 2, 0}});
  const int rotation = t.add(std::vector<glm::vec4>{{0, 0, 0, 1}, {s, 0, 0, s}});  // identity; 90 deg about X
  const int scale = t.add(std::vector<glm::vec3>{{1, 1, 1}, {2, 2, 2}});
  // The instancing node: 90 degrees about Z, under a parent translated by (10, 0, 0).
  t.builder.add_node({{"name", "parent"}, {"translation", {10, 0, 0}}, {"children", {1}}});
  t.builder.doc["scenes"] = json::array({{{"nodes", {0}}}});
  t.builder.doc["scene"] = 0;
  t.builder.doc["extensionsUsed"] = {"EXT_mesh_gpu_instancing"};
  json node = {{"name", "batch"}, {"mesh", 0}, {"rotation", {0, 0, s, s}}};
  node["extensions"]["EXT_mesh_gpu_instancing"] = {
      {"attributes", {{"TRANSLATION", translation}, {"ROTATION", rotation}, {"SCALE", scale}}}};
  t.builder.add_node(node);
  const Scene scene = load_gltf(t.builder.write_gltf(test::fresh_test_dir(), "composed"));
  ASSERT_EQ(scene.meshes.size(), 1u);
  const Mesh& mesh = scene.meshes[0];
  ASSERT_EQ(mesh.positions.size(), 6u);
  // Instance 0, vertex (1,0,0): +T (2,0,0); node Rz90 (0,2,0); parent (10,2,0).
  expect_near(mesh.positions[1], {10, 2, 0});
  expect_near(mesh.positions[2], {9, 1, 0});  // (0,1,0) -> (1,1,0) -> (-1,1,0)
  expect_near(mesh.normals[0], {0, 0, 1});
  // Instance 1, vertex (1,0,0): S (2,0,0); Rx90 (2,0,0); T (2,2,0); Rz90 (-2,2,0); (8,2,0).
  expect_near(mesh.positions[4], {8, 2, 0});
  expect_near(mesh.positions[5], {8, 0, 2});  // (0,1,0) -> (0,2,0) -> (0,0,2) -> (0,2,2) -> (-2,0,2)
  expect_near(mesh.normals[3], {1, 0, 0});   // +Z -> Rx90 -Y -> Rz90 +X
  EXPECT_EQ(mesh.triangles[1], glm::uvec3(3, 4, 5));
  EXPECT_EQ(scene.info.gpu_instances, 2);
}

TEST(GltfInstancing, MirroringInstanceFlipsItsWinding) {
  InstancedTriangle t;
  const int translation = t.add(std::vector<glm::vec3>{{0, 0, 0}, {5, 0, 0}});
  const int scale = t.add(std::vector<glm::vec3>{{1, 1, 1}, {-1, 1, 1}});
  const Scene scene = load_gltf(t.write({{"TRANSLATION", translation}, {"SCALE", scale}}));
  const std::vector<WorldTriangle> triangles = world_triangles(scene);
  ASSERT_EQ(triangles.size(), 2u);
  EXPECT_EQ(scene.meshes[0].triangles[0], glm::uvec3(0, 1, 2));
  EXPECT_EQ(scene.meshes[0].triangles[1], glm::uvec3(3, 5, 4));  // the mirrored copy, reversed
  for (const WorldTriangle& w : triangles)
    for (int k = 0; k < 3; ++k) EXPECT_GT(glm::dot(geometric_normal(w), w.n[k]), 0.99f);
  expect_near(triangles[1].p[0], {5, 0, 0});
  expect_near(triangles[1].p[2], {4, 0, 0});  // (1,0,0) mirrored, then moved
}

TEST(GltfInstancing, NormalizedShortRotationsAreRead) {
  // The extension allows normalized BYTE / SHORT rotations: 90 degrees about Z.
  InstancedTriangle t;
  const int16_t c = 23170;  // round(sqrt(0.5) * 32767)
  const std::vector<int16_t> q = {0, 0, c, c};
  const int view = t.builder.add_view(q.data(), q.size() * sizeof(int16_t));
  const int rotation = t.builder.add_accessor(
      {{"bufferView", view}, {"componentType", 5122}, {"normalized", true}, {"count", 1}, {"type", "VEC4"}});
  const Scene scene = load_gltf(t.write({{"ROTATION", rotation}}));
  expect_near(scene.meshes[0].positions[1], {0, 1, 0});
  expect_near(scene.meshes[0].positions[2], {-1, 0, 0});
}

TEST(GltfInstancing, CustomAttributesAreIgnoredButCounted) {
  InstancedTriangle t;
  const int translation = t.add(std::vector<glm::vec3>{{0, 0, 0}, {2, 0, 0}});
  const int ids = t.add(std::vector<glm::vec2>{{0, 0}, {1, 0}});
  const Scene scene = load_gltf(t.write({{"TRANSLATION", translation}, {"_ID", ids}}));
  EXPECT_EQ(scene.triangle_count(), 2u);
  EXPECT_TRUE(scene.warnings.empty()) << scene.warnings.front();
}

TEST(GltfInstancing, NodeWithoutMeshIsIgnoredWithAWarning) {
  InstancedTriangle t;
  const int translation = t.add(std::vector<glm::vec3>{{0, 0, 0}});
  json node = {{"name", "empty"}};
  node["extensions"]["EXT_mesh_gpu_instancing"] = {{"attributes", {{"TRANSLATION", translation}}}};
  t.builder.set_scene({t.builder.add_node(node)});
  t.builder.doc["extensionsUsed"] = {"EXT_mesh_gpu_instancing"};
  const Scene scene = load_gltf(t.builder.write_gltf(test::fresh_test_dir(), "empty"));
  EXPECT_TRUE(scene.meshes.empty());
  EXPECT_TRUE(any_warning_has(scene, "node 0 'empty' EXT_mesh_gpu_instancing ignored: the node has no mesh"));
}

TEST(GltfInstancingErrors, CountsMustAgree) {
  InstancedTriangle t;
  const int translation = t.add(std::vector<glm::vec3>{{0, 0, 0}, {1, 0, 0}});
  const int scale = t.add(std::vector<glm::vec3>{{1, 1, 1}, {1, 1, 1}, {1, 1, 1}});
  EXPECT_THAT(load_error(t.write({{"TRANSLATION", translation}, {"SCALE", scale}})),
              HasSubstr("instanced.gltf: node 0 'batch' EXT_mesh_gpu_instancing attribute TRANSLATION "
                        "(accessor 3) has count 2 but SCALE has count 3: all must be equal"));
}

TEST(GltfInstancingErrors, MissingAccessor) {
  InstancedTriangle t;
  EXPECT_THAT(load_error(t.write({{"TRANSLATION", 42}})),
              HasSubstr("node 0 'batch' EXT_mesh_gpu_instancing attribute TRANSLATION refers to accessor 42, "
                        "which does not exist (3 accessors)"));
}

TEST(GltfInstancingErrors, WrongAccessorTypes) {
  {
    InstancedTriangle t;
    const int translation = t.add(std::vector<glm::vec4>{{0, 0, 0, 1}});
    EXPECT_THAT(load_error(t.write({{"TRANSLATION", translation}})),
                AllOf(HasSubstr("(TRANSLATION of node 0 'batch' EXT_mesh_gpu_instancing)"),
                      HasSubstr("has type VEC4, expected VEC3")));
  }
  {
    InstancedTriangle t;
    const int rotation = t.add(std::vector<glm::vec3>{{0, 0, 0}});
    EXPECT_THAT(load_error(t.write({{"ROTATION", rotation}})),
                AllOf(HasSubstr("(ROTATION of node 0 'batch' EXT_mesh_gpu_instancing)"),
                      HasSubstr("has type VEC3, expected VEC4")));
  }
  {  // Unsigned components cannot hold a quaternion's signs: not in the extension.
    InstancedTriangle t;
    const std::vector<uint16_t> q = {0, 0, 0, 65535};
    const int view = t.builder.add_view(q.data(), q.size() * sizeof(uint16_t));
    const int rotation = t.builder.add_accessor(
        {{"bufferView", view}, {"componentType", 5123}, {"normalized", true}, {"count", 1}, {"type", "VEC4"}});
    EXPECT_THAT(load_error(t.write({{"ROTATION", rotation}})),
                AllOf(HasSubstr("(ROTATION of node 0 'batch' EXT_mesh_gpu_instancing)"),
                      HasSubstr("UNSIGNED_SHORT")));
  }
  {  // Refused by the schema check or by the loader, whichever sees it first.
    InstancedTriangle t;
    EXPECT_THAT(load_error(t.write({{"TRANSLATION", "zero"}})),
                AllOf(HasSubstr("'batch'"), HasSubstr("EXT_mesh_gpu_instancing"), HasSubstr("TRANSLATION")));
  }
}

TEST(GltfInstancingErrors, NonFiniteValuesAndZeroRotations) {
  {
    InstancedTriangle t;
    const int scale = t.add(std::vector<glm::vec3>{{1, 1, 1}, {1, std::nanf(""), 1}});
    EXPECT_THAT(load_error(t.write({{"SCALE", scale}})),
                AllOf(HasSubstr("(SCALE of node 0 'batch' EXT_mesh_gpu_instancing)"),
                      HasSubstr("element 1 is not finite")));
  }
  {
    InstancedTriangle t;
    const int rotation = t.add(std::vector<glm::vec4>{{0, 0, 0, 1}, {0, 0, 0, 0}});
    EXPECT_THAT(load_error(t.write({{"ROTATION", rotation}})),
                HasSubstr("node 0 'batch' EXT_mesh_gpu_instancing instance 1 ROTATION is a zero quaternion"));
  }
}

TEST(GltfInstancingErrors, NoAttributes) {
  // Refused by the schema check or by the loader, whichever sees it first.
  InstancedTriangle t;
  EXPECT_THAT(load_error(t.write(json::object())),
              AllOf(HasSubstr("'batch'"), HasSubstr("EXT_mesh_gpu_instancing"), HasSubstr("attributes")));
}

TEST(GltfInstancingErrors, TooManyBakedVerticesAreRefusedBeforeReading) {
  // 2^24 instances in a few bytes of JSON (no bufferView: all zeros) of a 3-vertex triangle.
  InstancedTriangle t;
  const int translation =
      t.builder.add_accessor({{"componentType", 5126}, {"count", 1 << 24}, {"type", "VEC3"}});
  EXPECT_THAT(load_error(t.write({{"TRANSLATION", translation}})),
              AllOf(HasSubstr("node 0 'batch' EXT_mesh_gpu_instancing draws 16777216 instances of mesh 0 'tri' "
                              "(3 vertices each)"),
                    HasSubstr("more than the 33554432 vertices")));
}

}  // namespace
}  // namespace phyir::scenes
