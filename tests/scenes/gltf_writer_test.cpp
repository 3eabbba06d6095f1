// The glTF writer: lights, node extras, copied JPEG and PNG textures, materials for real
// furniture (alpha, double-sided, normal and emissive maps, glass) and the scene's environment
// round-trip through load_gltf (whose schema check runs on every load); the same document
// gives the same bytes; bad documents fail naming the object; the Khronos validator finds
// no error.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <fstream>
#include <map>

#include "gltf_test_helpers.h"
#include "phyir/core/atomic_file.h"
#include "phyir/core/error.h"
#include "phyir/core/image_io.h"
#include "phyir/scenes/gltf_loader.h"
#include "phyir/scenes/gltf_writer.h"

namespace phyir::scenes {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;
using ::testing::HasSubstr;
using Type = PunctualLight::Type;

// A 4 x 4 RGB checker written as `path` (the extension picks PNG or JPEG).
void write_checker(const fs::path& path) {
  Image image(4, 4, 3);
  for (int y = 0; y < 4; ++y)
    for (int x = 0; x < 4; ++x)
      for (int c = 0; c < 3; ++c) image.at(x, y, c) = (x + y) % 2 == 0 ? 0.9f : 0.1f + 0.2f * c;
  write_image(path, image);
}

// A unit quad in the XZ plane facing +Y, with UVs.
GltfMesh quad(const std::string& name, int material, float y) {
  GltfMesh m;
  m.name = name;
  m.material = material;
  m.positions = {{0, y, 0}, {0, y, 1}, {1, y, 1}, {1, y, 0}};
  m.normals.assign(4, glm::vec3(0, 1, 0));
  m.texcoords0 = {{0, 0}, {0, 1}, {1, 1}, {1, 0}};
  m.indices = {0, 1, 2, 0, 2, 3};
  return m;
}

GltfLight light(const std::string& name, Type type, glm::vec3 position, glm::vec3 direction, glm::vec3 radiometric) {
  GltfLight l;
  l.name = name;
  l.type = type;
  l.position = position;
  l.direction = direction;
  l.set_radiometric(radiometric);
  return l;
}

// Point, spot and directional lights, the spot and sun along awkward directions (+Z is the
// half turn, straight down the common case).
std::vector<GltfLight> lights() {
  std::vector<GltfLight> out = {
      light("lamp", Type::Point, {0.5f, 2.2f, 0.5f}, {0, 0, -1}, {0.8f, 0.5f, 0.2f}),
      light("spot", Type::Spot, {1.0f, 2.5f, -0.25f}, {0, -1, 0}, {3.0f, 3.0f, 2.5f}),
      light("sun", Type::Directional, {0, 10, 0}, glm::normalize(glm::vec3(0.3f, -0.8f, 0.52f)), {120.0f, 110.0f, 95.0f}),
      light("back", Type::Directional, {0, 0, 0}, {0, 0, 1}, {0.001f, 0.002f, 0.003f})};
  out[1].inner_cone_angle = 0.2f;
  out[1].outer_cone_angle = 0.7f;
  out[0].range = 12.5f;
  out[0].extras = {{"asset", "ceiling lamp"}};
  return out;
}

// The furniture a generator writes: textured wood (JPEG from memory, KHR_texture_transform),
// a leaf cut-out (MASK, double-sided, PNG copied from a file, clamped), a lamp shade (emissive
// texture, BLEND) and glass; every mesh node carries its asset's credits.
struct Fixture {
  fs::path dir;      // output folder
  fs::path sources;  // where the input images live
  GltfDocument doc;
};

Fixture furnished_document() {
  Fixture f;
  f.dir = test::fresh_test_dir();
  f.sources = f.dir / "sources";
  fs::create_directories(f.sources);
  write_checker(f.sources / "wood.jpg");
  write_checker(f.sources / "leaf.png");
  GltfDocument& doc = f.doc;
  doc.generator = "phyir writer test";
  doc.textures.push_back({"tex/wood.jpg", {{}, read_file(f.sources / "wood.jpg")}, {}});
  doc.textures.push_back({"tex/leaf.png", {f.sources / "leaf.png", {}}, {GltfWrap::ClampToEdge, GltfWrap::MirroredRepeat}});
  doc.textures.push_back({"tex/wood.jpg", {{}, read_file(f.sources / "wood.jpg")}, {GltfWrap::ClampToEdge, GltfWrap::ClampToEdge}});

  GltfMaterial wood;
  wood.name = "wood";
  wood.base_color_texture.texture = 0;
  wood.base_color_texture.transform = TextureTransform{{0.25f, 0.5f}, {2.0f, 3.0f}, 0.5f};
  wood.normal_texture.texture = 1;
  wood.normal_scale = 0.5f;
  wood.metallic_factor = 0.0f;
  wood.roughness_factor = 0.6f;
  GltfMaterial leaf;
  leaf.name = "leaf";
  leaf.base_color_texture.texture = 1;
  leaf.alpha_mode = AlphaMode::Mask;
  leaf.alpha_cutoff = 0.3f;
  leaf.double_sided = true;
  GltfMaterial shade;
  shade.name = "shade";
  shade.emissive_factor = glm::vec3(1.0f, 0.9f, 0.7f);
  shade.emissive_texture.texture = 2;
  shade.emissive_strength = 40.0f;
  shade.alpha_mode = AlphaMode::Blend;
  shade.base_color_factor = glm::vec4(1.0f, 1.0f, 1.0f, 0.6f);
  GltfMaterial glass;
  glass.name = "glass";
  glass.transmission_factor = 1.0f;
  glass.ior = 1.5f;
  glass.roughness_factor = 0.0f;
  doc.materials = {wood, leaf, shade, glass};

  for (int m = 0; m < 4; ++m) {
    doc.meshes.push_back(quad(doc.materials[m].name, m, 0.5f * m));
    doc.meshes.back().extras = {{"asset", {{"name", doc.materials[m].name + " thing"},
                                           {"library", "sweethome3d-furniture"},
                                           {"creator", "someone"},
                                           {"licence", "CC-BY 4.0"}}}};
  }
  doc.cameras.push_back({"camera", {0.5f, 1.5f, 3.0f}, {0, 0, 0, 1}, 1.2f, 0.01f});
  doc.lights = lights();
  write_checker(f.sources / "sky.exr");
  doc.environment = GltfEnvironment{"sky.exr", {f.sources / "sky.exr", {}}, 2.5f};
  doc.scene_extras = {{"phyir", {{"preset", "test"}}}};
  return f;
}

json read_json(const fs::path& path) { return json::parse(read_file(path)); }

void expect_relative(const glm::vec3& got, const glm::vec3& want, float tolerance) {
  for (int c = 0; c < 3; ++c) EXPECT_NEAR(got[c], want[c], tolerance * std::abs(want[c])) << "channel " << c;
}

TEST(GltfWriter, LightsRoundTripThroughTheLoader) {
  Fixture f = furnished_document();
  write_gltf(f.dir / "room.gltf", f.doc);
  const Scene scene = load_gltf(f.dir / "room.gltf");
  const std::vector<GltfLight> written = lights();
  ASSERT_EQ(scene.lights.size(), written.size());
  for (size_t i = 0; i < written.size(); ++i) {
    SCOPED_TRACE(written[i].name);
    const PunctualLight& l = scene.lights[i];
    EXPECT_EQ(l.name, written[i].name);
    EXPECT_EQ(l.type, written[i].type);
    if (l.type != Type::Directional) {
      for (int c = 0; c < 3; ++c) EXPECT_NEAR(l.position[c], written[i].position[c], 1e-6f);
    }
    if (l.type != Type::Point) {
      for (int c = 0; c < 3; ++c) EXPECT_NEAR(l.direction[c], glm::normalize(written[i].direction)[c], 1e-6f);
    }
  }
  // W/sr and W/m^2 back within 1e-5 relative (683 lm/W both ways).
  expect_relative(scene.lights[0].radiometric(), {0.8f, 0.5f, 0.2f}, 1e-5f);
  expect_relative(scene.lights[1].radiometric(), {3.0f, 3.0f, 2.5f}, 1e-5f);
  expect_relative(scene.lights[2].radiometric(), {120.0f, 110.0f, 95.0f}, 1e-5f);
  expect_relative(scene.lights[3].radiometric(), {0.001f, 0.002f, 0.003f}, 1e-5f);
  EXPECT_FLOAT_EQ(scene.lights[1].inner_cone_angle, 0.2f);
  EXPECT_FLOAT_EQ(scene.lights[1].outer_cone_angle, 0.7f);
  EXPECT_FLOAT_EQ(scene.lights[0].range, 12.5f);
  EXPECT_EQ(scene.info.extensions_required, std::vector<std::string>{"KHR_lights_punctual"});
}

TEST(GltfWriter, TexturesAreCopiedWithTheirTypeSamplerAndTransform) {
  Fixture f = furnished_document();
  write_gltf(f.dir / "room.gltf", f.doc);
  EXPECT_EQ(read_file(f.dir / "tex/wood.jpg"), read_file(f.sources / "wood.jpg"));
  EXPECT_EQ(read_file(f.dir / "tex/leaf.png"), read_file(f.sources / "leaf.png"));
  const json gltf = read_json(f.dir / "room.gltf");
  // Two images (textures 0 and 2 share wood.jpg), three samplers.
  ASSERT_EQ(gltf["images"].size(), 2u);
  EXPECT_EQ(gltf["images"][0], json({{"uri", "tex/wood.jpg"}, {"mimeType", "image/jpeg"}}));
  EXPECT_EQ(gltf["images"][1], json({{"uri", "tex/leaf.png"}, {"mimeType", "image/png"}}));
  EXPECT_EQ(gltf["samplers"].size(), 3u);
  EXPECT_EQ(gltf["textures"][2], json({{"sampler", 2}, {"source", 0}}));
  EXPECT_EQ(gltf["samplers"][1]["wrapS"], 33071);
  EXPECT_EQ(gltf["samplers"][1]["wrapT"], 33648);

  const Scene scene = load_gltf(f.dir / "room.gltf");
  const Material& wood = scene.materials[0];
  ASSERT_TRUE(wood.base_color_texture.present());
  EXPECT_EQ(wood.base_color_texture.transform.offset, glm::vec2(0.25f, 0.5f));
  EXPECT_EQ(wood.base_color_texture.transform.scale, glm::vec2(2.0f, 3.0f));
  EXPECT_FLOAT_EQ(wood.base_color_texture.transform.rotation, 0.5f);
  EXPECT_TRUE(wood.normal_texture.present());
  EXPECT_FLOAT_EQ(wood.normal_scale, 0.5f);
  // Decoded: the PNG read as data (the normal map) has the checker's code 230 at texel (0, 0).
  const Texture& normal = scene.textures[static_cast<size_t>(wood.normal_texture.texture)];
  EXPECT_NEAR(normal.sample({0.125f, 0.125f}).x, 230.0f / 255.0f, 1e-6f);
  EXPECT_NEAR(normal.sample({0.375f, 0.125f}).x, 26.0f / 255.0f, 1e-6f);
  EXPECT_EQ(normal.wrap_s, WrapMode::ClampToEdge);
  EXPECT_EQ(normal.wrap_t, WrapMode::MirroredRepeat);
  const Texture& jpeg = scene.textures[static_cast<size_t>(wood.base_color_texture.texture)];
  EXPECT_LT(jpeg.sample({0.375f, 0.125f}).x, 0.5f * jpeg.sample({0.125f, 0.125f}).x);
}

TEST(GltfWriter, FurnitureMaterialsRoundTrip) {
  Fixture f = furnished_document();
  write_gltf(f.dir / "room.gltf", f.doc);
  const Scene scene = load_gltf(f.dir / "room.gltf");
  ASSERT_EQ(scene.materials.size(), 4u);
  const Material& leaf = scene.materials[1];
  EXPECT_EQ(leaf.alpha_mode, AlphaMode::Mask);
  EXPECT_FLOAT_EQ(leaf.alpha_cutoff, 0.3f);
  EXPECT_TRUE(leaf.double_sided);
  const Material& shade = scene.materials[2];
  EXPECT_EQ(shade.alpha_mode, AlphaMode::Blend);
  EXPECT_TRUE(shade.emissive_texture.present());
  expect_relative(shade.emission(), {40.0f, 36.0f, 28.0f}, 1e-6f);
  EXPECT_FLOAT_EQ(shade.base_color_factor.w, 0.6f);
  const Material& glass = scene.materials[3];
  EXPECT_FLOAT_EQ(glass.transmission_factor, 1.0f);
  EXPECT_FLOAT_EQ(glass.ior, 1.5f);
  // The normal-mapped wood has the tangents the loader derives; untextured glass no UVs.
  ASSERT_EQ(scene.meshes[0].tangents.size(), 4u);
  for (const glm::vec4& t : scene.meshes[0].tangents) {
    EXPECT_NEAR(glm::length(glm::vec3(t)), 1.0f, 1e-6f);
    EXPECT_NEAR(glm::dot(glm::vec3(t), glm::vec3(0, 1, 0)), 0.0f, 1e-6f);
    EXPECT_EQ(std::abs(t.w), 1.0f);
  }
  EXPECT_TRUE(scene.meshes[3].texcoords0.empty());
  EXPECT_FALSE(scene.materials[0].double_sided);
  EXPECT_EQ(scene.materials[0].alpha_mode, AlphaMode::Opaque);
}

TEST(GltfWriter, NodesCarryNamesAndExtras) {
  Fixture f = furnished_document();
  write_gltf(f.dir / "room.gltf", f.doc);
  const json gltf = read_json(f.dir / "room.gltf");
  const json& nodes = gltf["nodes"];
  ASSERT_EQ(nodes.size(), 4u + 1u + 4u);  // meshes, camera, lights
  EXPECT_EQ(nodes[0]["name"], "wood");
  EXPECT_EQ(nodes[0]["extras"]["asset"]["library"], "sweethome3d-furniture");
  EXPECT_EQ(nodes[3]["extras"]["asset"]["licence"], "CC-BY 4.0");
  EXPECT_FALSE(nodes[4].contains("extras"));  // the camera
  EXPECT_EQ(nodes[5]["name"], "lamp");
  EXPECT_EQ(nodes[5]["extras"]["asset"], "ceiling lamp");
  EXPECT_FALSE(nodes[5].contains("rotation"));  // a point light needs none
  EXPECT_EQ(gltf["extensionsUsed"], json({"KHR_lights_punctual", "KHR_materials_emissive_strength",
                                          "KHR_materials_ior", "KHR_materials_transmission", "KHR_texture_transform"}));
}

TEST(GltfWriter, EnvironmentIsCopiedAndDeclaredInTheSceneExtras) {
  Fixture f = furnished_document();
  write_gltf(f.dir / "room.gltf", f.doc);
  EXPECT_EQ(read_file(f.dir / "sky.exr"), read_file(f.sources / "sky.exr"));
  const json extras = read_json(f.dir / "room.gltf")["scenes"][0]["extras"];
  EXPECT_EQ(extras["phyir"]["environment"], json({{"uri", "sky.exr"}, {"scale", 2.5}}));
  EXPECT_EQ(extras["phyir"]["preset"], "test");  // the document's own extras kept
  const Scene scene = load_gltf(f.dir / "room.gltf");
  ASSERT_TRUE(scene.environment.has_value());
  EXPECT_EQ(scene.environment->uri, "sky.exr");
  EXPECT_EQ(scene.environment->path, f.dir / "sky.exr");
  EXPECT_EQ(scene.environment->scale, 2.5f);
}

std::map<std::string, std::string> folder_bytes(const fs::path& dir) {
  std::map<std::string, std::string> files;
  for (const auto& entry : fs::recursive_directory_iterator(dir))
    if (entry.is_regular_file()) files[fs::relative(entry.path(), dir).string()] = read_file(entry.path());
  return files;
}

TEST(GltfWriter, SameDocumentSameBytes) {
  Fixture f = furnished_document();
  write_gltf(f.dir / "a" / "room.gltf", f.doc);
  write_gltf(f.dir / "b" / "room.gltf", f.doc);
  const auto a = folder_bytes(f.dir / "a"), b = folder_bytes(f.dir / "b");
  EXPECT_EQ(a.size(), 5u);  // room.gltf, room.bin, two images, sky.exr: no temporary left behind
  EXPECT_EQ(a, b);
}

TEST(GltfWriter, WithoutTheNewFeaturesTheOutputIsAsBefore) {
  // What the room generator writes: textures it wrote itself, default samplers, no lights.
  GltfDocument doc;
  doc.generator = "g";
  doc.textures.push_back({"room_0_wood.png", {}, {}});
  GltfMaterial m;
  m.name = "wood";
  m.base_color_texture.texture = 0;
  doc.materials.push_back(m);
  doc.meshes.push_back(quad("floor", 0, 0.0f));
  const json gltf = json::parse(encode_gltf(doc, "room_0.bin").json);
  EXPECT_EQ(gltf["images"], json::parse(R"([{"uri": "room_0_wood.png"}])"));
  EXPECT_EQ(gltf["samplers"], json::parse(R"([{"magFilter": 9729, "minFilter": 9987, "wrapS": 10497, "wrapT": 10497}])"));
  EXPECT_EQ(gltf["materials"][0], json::parse(R"({"name": "wood", "pbrMetallicRoughness": {"baseColorFactor":
      [1.0, 1.0, 1.0, 1.0], "baseColorTexture": {"index": 0}, "metallicFactor": 1.0, "roughnessFactor": 1.0}})"));
  EXPECT_FALSE(gltf.contains("extensionsUsed"));
  EXPECT_FALSE(gltf.contains("extensionsRequired"));
  EXPECT_FALSE(gltf.contains("extensions"));
  EXPECT_FALSE(gltf["nodes"][0].contains("extras"));
  EXPECT_TRUE(encode_gltf(doc, "room_0.bin").side_files.empty());
}

std::string encode_error(const GltfDocument& doc) {
  try {
    encode_gltf(doc, "x.bin");
  } catch (const Error& e) {
    return e.what();
  }
  return "(no error)";
}

TEST(GltfWriter, BadDocumentsFailNamingTheObject) {
  const Fixture f = furnished_document();
  GltfDocument doc = f.doc;
  doc.textures[1].uri = "../leaf.png";
  EXPECT_THAT(encode_error(doc), HasSubstr("texture 1 uri '../leaf.png' has a '.' or '..' component"));
  doc = f.doc;
  doc.textures[1].uri = "my leaf.png";
  EXPECT_THAT(encode_error(doc), HasSubstr("would need percent-encoding"));
  doc = f.doc;
  doc.textures[1].uri = "leaf.jpg";
  EXPECT_THAT(encode_error(doc), HasSubstr("texture 1 'leaf.jpg' holds a PNG image: its uri must end in .png"));
  doc = f.doc;
  doc.textures[0].source.bytes = "GIF89a....";
  EXPECT_THAT(encode_error(doc), HasSubstr("texture 0 'tex/wood.jpg' (10 bytes in memory) is neither PNG nor JPEG"));
  doc = f.doc;
  doc.textures[1].source.file = f.sources / "missing.png";
  EXPECT_THAT(encode_error(doc), HasSubstr("missing.png not found"));
  doc = f.doc;
  doc.textures[2].source.bytes = "\xFF\xD8\xFF other bytes";
  EXPECT_THAT(encode_error(doc), HasSubstr("textures 0 and 2 give uri 'tex/wood.jpg' different sources"));
  doc = f.doc;
  doc.lights[0].color.y = 1.5f;
  EXPECT_THAT(encode_error(doc), HasSubstr("light 0 ('lamp') color[1] is 1.5: must be in [0, 1]"));
  doc = f.doc;
  doc.lights[1].inner_cone_angle = 0.9f;
  EXPECT_THAT(encode_error(doc), HasSubstr("light 1 ('spot') cone angles 0.9 and 0.7"));
  doc = f.doc;
  doc.lights[2].direction = glm::vec3(0.0f);
  EXPECT_THAT(encode_error(doc), HasSubstr("light 2 ('sun') has no direction"));
  doc = f.doc;
  doc.meshes[0].texcoords0.clear();
  EXPECT_THAT(encode_error(doc), HasSubstr("mesh 0 ('wood') has no texture coordinates but its material 'wood'"));
  doc = f.doc;
  doc.environment->uri = "tex/leaf.png";
  EXPECT_THAT(encode_error(doc), HasSubstr("two files would be written as 'tex/leaf.png'"));
  doc = f.doc;
  doc.scene_extras["phyir"]["environment"] = "sky.hdr";
  EXPECT_THAT(encode_error(doc), HasSubstr("scene_extras.phyir.environment is set and so is the document's"));
}

TEST(GltfWriter, SetRadiometricUsesTheLargestChannel) {
  GltfLight l;
  l.set_radiometric({2.0f, 1.0f, 0.5f});
  EXPECT_FLOAT_EQ(l.intensity, 2.0f * 683.0f);
  EXPECT_EQ(l.color, glm::vec3(1.0f, 0.5f, 0.25f));
  l.set_radiometric(glm::vec3(0.0f));
  EXPECT_EQ(l.intensity, 0.0f);
  EXPECT_EQ(l.color, glm::vec3(1.0f));
}

TEST(GltfWriter, KhronosValidatorFindsNoError) {
  if (std::system("command -v node >/dev/null 2>&1 && command -v npm >/dev/null 2>&1") != 0)
    GTEST_SKIP() << "node and npm are needed for the Khronos glTF validator";
  Fixture f = furnished_document();
  write_gltf(f.dir / "room.gltf", f.doc);
  const fs::path out = f.dir / "validator.txt", err = f.dir / "validator.err";
  const std::string script = std::string(PHYIR_SOURCE_ROOT) + "/scripts/gltf_validate.sh";
  const std::string files = (f.dir / "room.gltf").string();
  const int status = std::system(("bash " + script + " --fail-on-warnings " + files + " >" + out.string() +
                                  " 2>" + err.string())
                                     .c_str());
  if (!WIFEXITED(status) || WEXITSTATUS(status) == 2)
    GTEST_SKIP() << "the validator could not be installed or run: " << read_file(err);
  EXPECT_EQ(WEXITSTATUS(status), 0) << read_file(out) << read_file(err);
  EXPECT_THAT(read_file(out), HasSubstr("0 errors, 0 warnings, 0 infos"));
  std::printf("[writer] validator: %s", read_file(out).c_str());
}

}  // namespace
}  // namespace phyir::scenes
