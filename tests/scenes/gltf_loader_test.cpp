// glTF loader features on small files built in each test: transforms, winding, generated
// normals and tangents, attributes, primitive modes, materials and extensions, cameras,
// scene selection, GLB.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>

#include "gltf_test_helpers.h"
#include "phyir/core/image_io.h"
#include "phyir/scenes/gltf_loader.h"

namespace phyir::scenes {
namespace {

using nlohmann::json;
using test::GltfBuilder;
using ::testing::Contains;
using ::testing::HasSubstr;

constexpr float kTol = 1e-5f;

void expect_near(const glm::vec3& actual, const glm::vec3& expected, float tol = kTol) {
  EXPECT_NEAR(actual.x, expected.x, tol);
  EXPECT_NEAR(actual.y, expected.y, tol);
  EXPECT_NEAR(actual.z, expected.z, tol);
}

glm::vec3 geometric_normal(const Mesh& mesh, const glm::uvec3& t) {
  return glm::normalize(
      glm::cross(mesh.positions[t.y] - mesh.positions[t.x], mesh.positions[t.z] - mesh.positions[t.x]));
}

bool any_warning_has(const Scene& scene, const std::string& text) {
  for (const std::string& w : scene.warnings)
    if (w.find(text) != std::string::npos) return true;
  return false;
}

// One triangle mesh under `node` (which gets "mesh": 0), written and loaded.
Scene load_triangle_under(json node, const std::vector<glm::vec3>& normals = {}) {
  GltfBuilder b;
  b.add_triangles("tri", test::unit_triangle(), {0, 1, 2}, normals);
  node["mesh"] = 0;
  b.set_scene({b.add_node(node)});
  return load_gltf(b.write_gltf(test::fresh_test_dir(), "tri"));
}

TEST(GltfTransforms, TrsHierarchyBakesVertexPosition) {
  GltfBuilder b;
  b.add_triangles("tri", test::unit_triangle(), {0, 1, 2});
  const int child = b.add_node({{"mesh", 0}, {"translation", {1, 0, 0}}});
  const float s = std::sqrt(0.5f);  // 90 degrees about +Z
  const int parent = b.add_node(
      {{"children", {child}}, {"translation", {1, 2, 3}}, {"rotation", {0, 0, s, s}}, {"scale", {2, 2, 2}}});
  b.set_scene({parent});
  const Scene scene = load_gltf(b.write_gltf(test::fresh_test_dir(), "trs"));
  ASSERT_EQ(scene.meshes.size(), 1u);
  // Vertex (1,0,0): child translate -> (2,0,0); scale 2 -> (4,0,0); rotate -> (0,4,0); translate.
  expect_near(scene.meshes[0].positions[1], {1, 6, 3});
  expect_near(scene.meshes[0].positions[0], {1, 4, 3});
}

TEST(GltfTransforms, ColumnMajorMatrix) {
  // Columns: x -> x, y -> z, z -> -y (90 degrees about X), then translation (5,0,0).
  const Scene scene = load_triangle_under({{"matrix", {1, 0, 0, 0, 0, 0, 1, 0, 0, -1, 0, 0, 5, 0, 0, 1}}});
  expect_near(scene.meshes[0].positions[2], {5, 0, 1});  // (0,1,0)
  expect_near(scene.meshes[0].positions[1], {6, 0, 0});  // (1,0,0)
}

TEST(GltfTransforms, NegativeScaleFlipsWindingToMatchNormals) {
  const Scene scene = load_triangle_under({{"scale", {-1, 1, 1}}}, {{0, 0, 1}, {0, 0, 1}, {0, 0, 1}});
  const Mesh& mesh = scene.meshes[0];
  for (const glm::uvec3& t : mesh.triangles) {
    const glm::vec3 g = geometric_normal(mesh, t);
    for (int k = 0; k < 3; ++k) EXPECT_GT(glm::dot(g, mesh.normals[t[k]]), 0.99f);
  }
}

TEST(GltfTransforms, NormalsUseInverseTransposeAndAreRenormalised) {
  // A triangle in the plane x + y = 1; scaling x by 2 turns the plane into x/2 + y = 1.
  GltfBuilder b;
  const glm::vec3 n = glm::normalize(glm::vec3(1, 1, 0));
  b.add_triangles("slanted", {{1, 0, 0}, {0, 1, 0}, {1, 0, 1}}, {0, 1, 2}, {n, n, n});
  b.set_scene({b.add_node({{"mesh", 0}, {"scale", {2, 1, 1}}})});
  const Scene scene = load_gltf(b.write_gltf(test::fresh_test_dir(), "slanted"));
  const Mesh& mesh = scene.meshes[0];
  expect_near(mesh.normals[0], glm::normalize(glm::vec3(0.5f, 1, 0)));
  EXPECT_NEAR(glm::dot(mesh.normals[0], mesh.positions[1] - mesh.positions[0]), 0.0f, kTol);
  EXPECT_NEAR(glm::length(mesh.normals[0]), 1.0f, kTol);
}

TEST(GltfTransforms, TangentsFollowTheTransformAndMirrorHandedness) {
  GltfBuilder b;
  json primitive = {{"attributes",
                     {{"POSITION", b.add_floats(test::unit_triangle())},
                      {"NORMAL", b.add_floats(std::vector<glm::vec3>(3, {0, 0, 1}))},
                      {"TANGENT", b.add_floats(std::vector<glm::vec4>(3, {1, 0, 0, 1}))}}}};
  b.add_mesh("tangent", {primitive});
  const float s = std::sqrt(0.5f);
  const int rotated = b.add_node({{"mesh", 0}, {"rotation", {0, 0, s, s}}});
  const int mirrored = b.add_node({{"mesh", 0}, {"scale", {1, -1, 1}}});
  b.set_scene({rotated, mirrored});
  const Scene scene = load_gltf(b.write_gltf(test::fresh_test_dir(), "tangent"));
  ASSERT_EQ(scene.meshes.size(), 2u);
  expect_near(glm::vec3(scene.meshes[0].tangents[0]), {0, 1, 0});
  EXPECT_EQ(scene.meshes[0].tangents[0].w, 1.0f);
  // Mirroring y keeps T = +X and N = +Z, so cross(N, T) is still +Y while the true
  // bitangent, the mirrored +Y, is -Y: w must flip.
  expect_near(glm::vec3(scene.meshes[1].tangents[0]), {1, 0, 0});
  EXPECT_EQ(scene.meshes[1].tangents[0].w, -1.0f);
}

TEST(GltfGeometry, MissingNormalsBecomeFlatFaceNormals) {
  // Two triangles folded along their shared edge: smooth normals would differ from both faces.
  GltfBuilder b;
  b.add_triangles("folded", {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}}, {0, 1, 2, 0, 3, 1});
  b.set_scene({b.add_node({{"mesh", 0}})});
  const Scene scene = load_gltf(b.write_gltf(test::fresh_test_dir(), "folded"));
  const Mesh& mesh = scene.meshes[0];
  ASSERT_EQ(mesh.triangles.size(), 2u);
  ASSERT_EQ(mesh.normals.size(), mesh.positions.size());
  for (const glm::uvec3& t : mesh.triangles) {
    const glm::vec3 face = geometric_normal(mesh, t);
    for (int k = 0; k < 3; ++k) expect_near(mesh.normals[t[k]], face);
  }
  expect_near(mesh.normals[mesh.triangles[0].x], {0, 0, 1});
}

TEST(GltfGeometry, NormalMapWithoutTangentsGetsGeneratedTangents) {
  GltfBuilder b;
  // glTF UVs: u to the right, v downwards, on a quad facing +Z.
  const std::vector<glm::vec3> positions{{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}};
  const std::vector<glm::vec2> uvs{{0, 1}, {1, 1}, {1, 0}, {0, 0}};
  const std::filesystem::path dir = test::fresh_test_dir();
  write_image(dir / "flat_normal.png", Image(1, 1, 3, 0.5f));
  json primitive = {{"attributes",
                     {{"POSITION", b.add_floats(positions)},
                      {"NORMAL", b.add_floats(std::vector<glm::vec3>(4, {0, 0, 1}))},
                      {"TEXCOORD_0", b.add_floats(uvs)}}},
                    {"indices", b.add_indices(std::vector<uint16_t>{0, 1, 2, 0, 2, 3})},
                    {"material", 0}};
  b.add_mesh("quad", {primitive});
  b.doc["images"] = {{{"uri", "flat_normal.png"}}};
  b.doc["textures"] = {{{"source", 0}}};
  b.doc["materials"] = {{{"normalTexture", {{"index", 0}}}}};
  b.set_scene({b.add_node({{"mesh", 0}})});
  const Scene scene = load_gltf(b.write_gltf(dir, "quad"));
  const Mesh& mesh = scene.meshes[0];
  ASSERT_EQ(mesh.tangents.size(), 4u);
  for (const glm::vec4& t : mesh.tangents) {
    expect_near(glm::vec3(t), {1, 0, 0});
    EXPECT_EQ(t.w, 1.0f);  // cross(N, T) = +Y points up the image (decreasing v)
  }
}

TEST(GltfAttributes, NormalizedTexcoordsColoursStrideAndSmallIndices) {
  GltfBuilder b;
  // POSITION and NORMAL interleaved in one view with byteStride 24.
  const std::vector<float> interleaved{0, 0, 0, 0, 0, 1, 1, 0, 0, 0, 0, 1, 0, 1, 0, 0, 0, 1};
  const int view = b.add_view(interleaved.data(), interleaved.size() * sizeof(float), 24);
  const int position =
      b.add_accessor({{"bufferView", view}, {"componentType", 5126}, {"count", 3}, {"type", "VEC3"}});
  const int normal = b.add_accessor(
      {{"bufferView", view}, {"byteOffset", 12}, {"componentType", 5126}, {"count", 3}, {"type", "VEC3"}});
  const std::vector<uint8_t> uv_bytes{0, 255, 255, 128, 51, 0};
  const int uv_view = b.add_view(uv_bytes.data(), uv_bytes.size());
  const int uv = b.add_accessor({{"bufferView", uv_view},
                                 {"componentType", 5121},
                                 {"normalized", true},
                                 {"count", 3},
                                 {"type", "VEC2"}});
  const std::vector<uint16_t> colour_shorts{65535, 0, 0, 0, 65535, 0, 0, 0, 65535};
  const int colour_view = b.add_view(colour_shorts.data(), colour_shorts.size() * 2);
  const int colour = b.add_accessor({{"bufferView", colour_view},
                                     {"componentType", 5123},
                                     {"normalized", true},
                                     {"count", 3},
                                     {"type", "VEC3"}});
  const int indices = b.add_indices(std::vector<uint8_t>{0, 1, 2});
  b.add_mesh(
      "attrs",
      {{{"attributes", {{"POSITION", position}, {"NORMAL", normal}, {"TEXCOORD_0", uv}, {"COLOR_0", colour}}},
        {"indices", indices}}});
  b.set_scene({b.add_node({{"mesh", 0}})});
  const Scene scene = load_gltf(b.write_gltf(test::fresh_test_dir(), "attrs"));
  const Mesh& mesh = scene.meshes[0];
  expect_near(mesh.positions[2], {0, 1, 0});
  expect_near(mesh.normals[1], {0, 0, 1});
  EXPECT_FLOAT_EQ(mesh.texcoords0[0].y, 1.0f);
  EXPECT_FLOAT_EQ(mesh.texcoords0[1].y, 128.0f / 255.0f);
  EXPECT_FLOAT_EQ(mesh.texcoords0[2].x, 0.2f);
  EXPECT_EQ(mesh.colors[1], glm::vec4(0, 1, 0, 1));  // VEC3 colours get alpha 1
}

TEST(GltfAttributes, SparseAccessorSubstitutesValues) {
  GltfBuilder b;
  const int base = b.add_floats(test::unit_triangle());
  const std::vector<uint32_t> sparse_indices{2};
  const std::vector<glm::vec3> sparse_values{{0, 5, 0}};
  const int iv = b.add_view(sparse_indices.data(), 4);
  const int vv = b.add_view(sparse_values.data(), 12);
  b.doc["accessors"][base]["sparse"] = {{"count", 1},
                                        {"indices", {{"bufferView", iv}, {"componentType", 5125}}},
                                        {"values", {{"bufferView", vv}}}};
  b.add_mesh("sparse", {{{"attributes", {{"POSITION", base}}}}});
  b.set_scene({b.add_node({{"mesh", 0}})});
  const Scene scene = load_gltf(b.write_gltf(test::fresh_test_dir(), "sparse"));
  expect_near(scene.meshes[0].positions[2], {0, 5, 0});
  expect_near(scene.meshes[0].positions[1], {1, 0, 0});
}

TEST(GltfPrimitives, StripsAndFansBecomeTrianglesWithConsistentWinding) {
  GltfBuilder b;
  const int strip_positions =
      b.add_floats(std::vector<glm::vec3>{{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {1, 1, 0}, {0, 2, 0}});
  const int fan_positions =
      b.add_floats(std::vector<glm::vec3>{{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}, {-1, 1, 0}});
  b.add_mesh("modes", {{{"attributes", {{"POSITION", strip_positions}}}, {"mode", 5}},
                       {{"attributes", {{"POSITION", fan_positions}}}, {"mode", 6}}});
  b.set_scene({b.add_node({{"mesh", 0}})});
  const Scene scene = load_gltf(b.write_gltf(test::fresh_test_dir(), "modes"));
  ASSERT_EQ(scene.meshes.size(), 2u);
  EXPECT_EQ(scene.meshes[0].triangles.size(), 3u);
  EXPECT_EQ(scene.meshes[1].triangles.size(), 3u);
  for (const Mesh& mesh : scene.meshes)
    for (const glm::uvec3& t : mesh.triangles) expect_near(geometric_normal(mesh, t), {0, 0, 1});
}

TEST(GltfPrimitives, PointsAndLinesAreSkippedWithAWarning) {
  GltfBuilder b;
  const int positions = b.add_floats(test::unit_triangle());
  b.add_mesh("wire", {{{"attributes", {{"POSITION", positions}}}, {"mode", 1}},
                      {{"attributes", {{"POSITION", positions}}}}});
  b.set_scene({b.add_node({{"mesh", 0}})});
  const Scene scene = load_gltf(b.write_gltf(test::fresh_test_dir(), "wire"));
  EXPECT_EQ(scene.meshes.size(), 1u);
  EXPECT_EQ(scene.meshes[0].name, "wire/1");
  EXPECT_TRUE(any_warning_has(scene, "mesh 0 'wire' primitive 0 has mode LINES (1): skipped"));
}

TEST(GltfMaterials, DefaultMaterialIsAppendedOnce) {
  GltfBuilder b;
  const int positions = b.add_floats(test::unit_triangle());
  b.add_mesh("plain", {{{"attributes", {{"POSITION", positions}}}},
                       {{"attributes", {{"POSITION", positions}}}, {"material", 0}}});
  b.doc["materials"] = {{{"name", "red"}, {"pbrMetallicRoughness", {{"baseColorFactor", {1, 0, 0, 1}}}}}};
  b.add_node({{"mesh", 0}});
  b.add_node({{"mesh", 0}});
  b.set_scene({0, 1});
  const Scene scene = load_gltf(b.write_gltf(test::fresh_test_dir(), "plain"));
  ASSERT_EQ(scene.materials.size(), 2u);
  EXPECT_EQ(scene.meshes.size(), 4u);
  EXPECT_EQ(scene.meshes[0].material, 1);
  EXPECT_EQ(scene.meshes[2].material, 1);
  EXPECT_EQ(scene.meshes[1].material, 0);
  const Material& d = scene.materials[1];
  EXPECT_EQ(d.base_color_factor, glm::vec4(1.0f));
  EXPECT_EQ(d.metallic_factor, 1.0f);
  EXPECT_EQ(d.roughness_factor, 1.0f);
  EXPECT_EQ(scene.info.materials, 1);
}

// A triangle whose primitive uses material 0 = `material`, with a 1x1 texture available.
Scene load_with_material(const json& material, const std::vector<std::string>& extensions_used = {}) {
  GltfBuilder b;
  const std::filesystem::path dir = test::fresh_test_dir();
  write_image(dir / "white.png", Image(1, 1, 3, 1.0f));
  b.add_triangles("tri", test::unit_triangle(), {0, 1, 2}, {}, {{"material", 0}});
  b.doc["materials"] = json::array({material});  // not {material}: clang reads that as a copy (CWG 2137)
  b.doc["images"] = {{{"uri", "white.png"}}};
  b.doc["textures"] = {{{"source", 0}}};
  if (!extensions_used.empty()) b.doc["extensionsUsed"] = extensions_used;
  b.set_scene({b.add_node({{"mesh", 0}})});
  return load_gltf(b.write_gltf(dir, "material"));
}

TEST(GltfMaterials, CoreFactorsAlphaAndSidedness) {
  const Scene scene = load_with_material(
      {{"pbrMetallicRoughness",
        {{"baseColorFactor", {0.5, 0.25, 1, 0.75}}, {"metallicFactor", 0.2}, {"roughnessFactor", 0.7}}},
       {"alphaMode", "MASK"},
       {"alphaCutoff", 0.3},
       {"doubleSided", true}});
  const Material& m = scene.materials[0];
  EXPECT_EQ(m.base_color_factor, glm::vec4(0.5f, 0.25f, 1.0f, 0.75f));
  EXPECT_FLOAT_EQ(m.metallic_factor, 0.2f);
  EXPECT_FLOAT_EQ(m.roughness_factor, 0.7f);
  EXPECT_EQ(m.alpha_mode, AlphaMode::Mask);
  EXPECT_FLOAT_EQ(m.alpha_cutoff, 0.3f);
  EXPECT_TRUE(m.double_sided);
  EXPECT_TRUE(m.extensions.empty());
}

TEST(GltfMaterials, EmissiveStrengthScalesEmission) {
  const Scene scene =
      load_with_material({{"emissiveFactor", {1, 0.5, 0.25}},
                          {"extensions", {{"KHR_materials_emissive_strength", {{"emissiveStrength", 4}}}}}},
                         {"KHR_materials_emissive_strength"});
  const Material& m = scene.materials[0];
  EXPECT_TRUE(m.is_emissive());
  EXPECT_EQ(m.emission(), glm::vec3(4, 2, 1));
  EXPECT_THAT(m.extensions, Contains("KHR_materials_emissive_strength"));
  EXPECT_TRUE(scene.warnings.empty());
}

TEST(GltfMaterials, TransmissionAndIor) {
  const Scene scene =
      load_with_material({{"extensions",
                           {{"KHR_materials_transmission",
                             {{"transmissionFactor", 0.9}, {"transmissionTexture", {{"index", 0}}}}},
                            {"KHR_materials_ior", {{"ior", 1.33}}}}}},
                         {"KHR_materials_transmission", "KHR_materials_ior"});
  const Material& m = scene.materials[0];
  EXPECT_FLOAT_EQ(m.transmission_factor, 0.9f);
  EXPECT_FLOAT_EQ(m.ior, 1.33f);
  EXPECT_TRUE(m.is_transmissive());
  ASSERT_TRUE(m.transmission_texture.present());
  EXPECT_EQ(scene.textures[static_cast<size_t>(m.transmission_texture.texture)].encoding,
            TextureEncoding::LinearData);
  EXPECT_THAT(m.extensions, Contains("KHR_materials_transmission"));
  EXPECT_THAT(m.extensions, Contains("KHR_materials_ior"));
}

TEST(GltfMaterials, TextureTransformOnEveryTextureInfo) {
  const json transform = {{"KHR_texture_transform",
                           {{"offset", {0.5, 0.25}}, {"rotation", 1.5}, {"scale", {2, 3}}, {"texCoord", 1}}}};
  const Scene scene = load_with_material(
      {{"pbrMetallicRoughness", {{"baseColorTexture", {{"index", 0}, {"extensions", transform}}}}},
       {"emissiveTexture", {{"index", 0}, {"texCoord", 1}}},
       {"extensions",
        {{"KHR_materials_transmission",
          {{"transmissionTexture", {{"index", 0}, {"extensions", transform}}}}}}}},
      {"KHR_texture_transform", "KHR_materials_transmission"});
  const Material& m = scene.materials[0];
  for (const TextureSlot* slot : {&m.base_color_texture, &m.transmission_texture}) {
    EXPECT_EQ(slot->transform.offset, glm::vec2(0.5f, 0.25f));
    EXPECT_EQ(slot->transform.scale, glm::vec2(2.0f, 3.0f));
    EXPECT_FLOAT_EQ(slot->transform.rotation, 1.5f);
    EXPECT_EQ(slot->texcoord, 1);  // the extension's texCoord overrides the textureInfo's 0
  }
  EXPECT_TRUE(m.emissive_texture.transform.is_identity());
  EXPECT_EQ(m.emissive_texture.texcoord, 1);
  EXPECT_THAT(m.extensions, Contains("KHR_texture_transform"));
}

TEST(GltfExtensions, UnsupportedUsedExtensionsWarnWithTheirFallback) {
  const Scene scene = load_with_material(
      {{"extensions",
        {{"KHR_materials_clearcoat", {{"clearcoatFactor", 1}}}, {"KHR_materials_volume", json::object()}}}},
      {"KHR_materials_clearcoat", "KHR_materials_volume", "EXT_made_up"});
  EXPECT_THAT(scene.warnings, Contains("KHR_materials_clearcoat ignored: base layer only"));
  EXPECT_TRUE(
      any_warning_has(scene, "KHR_materials_volume ignored: glass treated as a solid refractive dielectric"));
  EXPECT_TRUE(any_warning_has(scene, "EXT_made_up ignored"));
  EXPECT_THAT(scene.materials[0].extensions, Contains("KHR_materials_clearcoat"));
  EXPECT_THAT(scene.info.extensions_used, Contains("EXT_made_up"));
}

TEST(GltfCameras, PerspectivePoseAndOrthographicWarning) {
  GltfBuilder b;
  b.doc["cameras"] = {
      {{"name", "eye"},
       {"type", "perspective"},
       {"perspective", {{"yfov", 0.9}, {"znear", 0.05}, {"aspectRatio", 2.0}}}},
      {{"type", "orthographic"}, {"orthographic", {{"xmag", 1}, {"ymag", 1}, {"znear", 0.1}, {"zfar", 10}}}}};
  const float s = std::sqrt(0.5f);  // 90 degrees about +Y: -Z turns to -X
  const int eye = b.add_node({{"camera", 0}, {"translation", {1, 2, 3}}, {"rotation", {0, s, 0, s}}});
  const int ortho = b.add_node({{"camera", 1}});
  b.set_scene({eye, ortho});
  const Scene scene = load_gltf(b.write_gltf(test::fresh_test_dir(), "cameras"));
  ASSERT_EQ(scene.cameras.size(), 2u);
  const Camera& c = scene.cameras[0];
  EXPECT_EQ(c.name, "eye");
  EXPECT_TRUE(c.perspective);
  expect_near(c.position, {1, 2, 3});
  expect_near(c.forward, {-1, 0, 0});
  expect_near(c.up, {0, 1, 0});
  EXPECT_FLOAT_EQ(c.yfov, 0.9f);
  EXPECT_FLOAT_EQ(c.aspect_ratio, 2.0f);
  EXPECT_FALSE(scene.cameras[1].perspective);
  EXPECT_TRUE(any_warning_has(scene, "camera 1 (on node 1) is orthographic"));
  EXPECT_EQ(scene.info.cameras, 2);
}

TEST(GltfScenes, DefaultSceneAndRootNodesWithoutScenes) {
  GltfBuilder b;
  b.add_triangles("tri", test::unit_triangle(), {0, 1, 2});
  b.add_node({{"mesh", 0}, {"translation", {10, 0, 0}}});
  b.add_node({{"mesh", 0}, {"translation", {20, 0, 0}}, {"children", {2}}});
  b.add_node({{"mesh", 0}});
  b.doc["scenes"] = {{{"nodes", {0}}}, {{"nodes", {1}}}};
  b.doc["scene"] = 1;
  const std::filesystem::path dir = test::fresh_test_dir();
  const Scene chosen = load_gltf(b.write_gltf(dir, "chosen"));
  EXPECT_EQ(chosen.info.default_scene, 1);
  EXPECT_EQ(chosen.info.mesh_instances, 2);
  EXPECT_FLOAT_EQ(chosen.bounds.min.x, 20.0f);

  b.doc.erase("scene");
  b.doc.erase("scenes");
  const Scene roots = load_gltf(b.write_gltf(dir, "roots"));  // roots: nodes 0 and 1
  EXPECT_EQ(roots.info.default_scene, -1);
  EXPECT_EQ(roots.info.mesh_instances, 3);
  EXPECT_FLOAT_EQ(roots.bounds.min.x, 10.0f);
  EXPECT_FLOAT_EQ(roots.bounds.max.x, 21.0f);
}

TEST(GltfScenes, CandidateViewpointsFromSceneExtras) {
  GltfBuilder b;
  b.add_triangles("tri", test::unit_triangle(), {0, 1, 2});
  b.set_scene({b.add_node({{"mesh", 0}})});
  b.doc["scenes"][0]["extras"] = {
      {"phyir", {{"candidate_viewpoints", {{1, 1.5, 2}, {-1, 1.2, 0}, {"bad"}}}}}};
  const Scene scene = load_gltf(b.write_gltf(test::fresh_test_dir(), "viewpoints"));
  ASSERT_EQ(scene.candidate_viewpoints.size(), 2u);
  expect_near(scene.candidate_viewpoints[1], {-1, 1.2f, 0});
  EXPECT_TRUE(any_warning_has(scene, "candidate_viewpoints entry 2 is not [x, y, z]"));
}

TEST(GltfContainer, GlbLoadsLikeGltf) {
  GltfBuilder b;
  b.add_triangles("tri", test::unit_triangle(), {0, 1, 2}, {{0, 0, 1}, {0, 0, 1}, {0, 0, 1}});
  b.set_scene({b.add_node({{"mesh", 0}, {"translation", {0, 0, -2}}})});
  const std::filesystem::path dir = test::fresh_test_dir();
  const Scene from_gltf = load_gltf(b.write_gltf(dir, "same"));
  const Scene from_glb = load_gltf(b.write_glb(dir, "same"));
  ASSERT_EQ(from_glb.meshes.size(), 1u);
  EXPECT_EQ(from_glb.meshes[0].positions, from_gltf.meshes[0].positions);
  EXPECT_EQ(from_glb.meshes[0].normals, from_gltf.meshes[0].normals);
  EXPECT_EQ(from_glb.meshes[0].triangles, from_gltf.meshes[0].triangles);
  EXPECT_EQ(from_glb.info.generator, "phyir loader tests");
}

TEST(GltfContainer, LoadTexturesFalseKeepsSlotsWithoutTexels) {
  GltfBuilder b;
  const std::filesystem::path dir = test::fresh_test_dir();
  write_image(dir / "white.png", Image(2, 2, 3, 1.0f));
  b.add_triangles("tri", test::unit_triangle(), {0, 1, 2}, {}, {{"material", 0}});
  b.doc["materials"] = {{{"pbrMetallicRoughness", {{"baseColorTexture", {{"index", 0}}}}}}};
  b.doc["images"] = {{{"uri", "white.png"}}};
  b.doc["textures"] = {{{"source", 0}}};
  b.set_scene({b.add_node({{"mesh", 0}})});
  const Scene scene = load_gltf(b.write_gltf(dir, "lazy"), LoadOptions{false});
  ASSERT_EQ(scene.textures.size(), 1u);
  EXPECT_FALSE(scene.textures[0].has_texels());
  EXPECT_EQ(scene.textures[0].name, "white.png");
  EXPECT_TRUE(scene.materials[0].base_color_texture.present());
}

}  // namespace
}  // namespace phyir::scenes
