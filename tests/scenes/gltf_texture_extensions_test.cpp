// Texture image extensions: EXT_texture_webp (decoded by OpenImageIO, preferred over the core
// source) and KHR_texture_basisu (no decoder: the core source with a warning, else an error).
// The WebP files are gltf-transform's output for textured_quad.gltf (data/gltf/webp/README.md).
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "gltf_test_helpers.h"
#include "phyir/core/error.h"
#include "phyir/core/image_io.h"
#include "phyir/scenes/gltf_loader.h"

namespace phyir::scenes {
namespace {

using nlohmann::json;
using ::testing::AllOf;
using ::testing::HasSubstr;

namespace fs = std::filesystem;

const fs::path kGltfData = fs::path(PHYIR_TEST_DATA_DIR) / "gltf";

const Texture& only_texture(const Scene& scene) {
  EXPECT_EQ(scene.textures.size(), 1u);
  return scene.textures.at(0);
}

bool any_warning_has(const Scene& scene, const std::string& text) {
  for (const std::string& w : scene.warnings)
    if (w.find(text) != std::string::npos) return true;
  return false;
}

std::string load_error(const fs::path& path) {
  try {
    load_gltf(path);
  } catch (const Error& e) {
    return e.what();
  }
  return "(loaded)";
}

// textured_quad.gltf's JSON, its .bin and checker.png copied into a fresh folder, ready to
// be edited and written there.
struct QuadFixture {
  fs::path dir = test::fresh_test_dir();
  json doc;

  QuadFixture() {
    std::ifstream(kGltfData / "textured_quad.gltf") >> doc;
    fs::copy_file(kGltfData / "textured_quad.bin", dir / "textured_quad.bin");
    fs::create_directories(dir / "textures");
    fs::copy_file(kGltfData / "textures" / "checker.png", dir / "textures" / "checker.png");
  }

  fs::path write(const std::string& name) {
    const fs::path path = dir / (name + ".gltf");
    std::ofstream(path) << doc.dump(1);
    return path;
  }

  // A KTX2 file's 12-byte identifier and nothing else: never decoded, only found.
  void add_ktx2(const std::string& file) {
    const unsigned char identifier[] = {0xAB, 'K', 'T', 'X', ' ', '2', '0', 0xBB, '\r', '\n', 0x1A, '\n'};
    test::write_bytes(dir / file, identifier, sizeof identifier);
  }
};

void expect_same_texels(const Texture& actual, const Texture& expected, float tolerance) {
  ASSERT_EQ(actual.width(), expected.width());
  ASSERT_EQ(actual.height(), expected.height());
  for (int y = 0; y < actual.height(); ++y)
    for (int x = 0; x < actual.width(); ++x)
      for (int c = 0; c < 4; ++c)
        EXPECT_NEAR(actual.texel(x, y)[c], expected.texel(x, y)[c], tolerance) << x << "," << y;
}

TEST(GltfTextureWebp, LosslessWebpDecodesToThePngTexels) {
  const Scene png = load_gltf(kGltfData / "textured_quad.gltf");
  const Scene webp = load_gltf(kGltfData / "webp" / "textured_quad_webp_lossless.glb");
  expect_same_texels(only_texture(webp), only_texture(png), 0.0f);
  EXPECT_TRUE(webp.warnings.empty()) << webp.warnings.front();
}

TEST(GltfTextureWebp, LossyWebpDecodesToThePngTexelsWithinItsLoss) {
  const Scene png = load_gltf(kGltfData / "textured_quad.gltf");
  const Scene webp = load_gltf(kGltfData / "webp" / "textured_quad_webp_lossy.glb");
  // The lossy file's worst texel is 250/255 where the PNG has 255: 0.955 once sRGB-decoded.
  expect_same_texels(only_texture(webp), only_texture(png), 0.05f);
}

TEST(GltfTextureWebp, WebpImageIsPreferredOverTheCoreSource) {
  QuadFixture quad;
  // The core source: a red image, so that the texels tell which image was used.
  Image red(2, 2, 3);
  for (size_t i = 0; i < red.pixels.size(); i += 3) red.pixels[i] = 1.0f;
  write_image(quad.dir / "textures" / "red.png", red);
  fs::copy_file(kGltfData / "webp" / "checker_lossless.webp", quad.dir / "textures" / "checker.webp");
  quad.doc["images"] = {{{"uri", "textures/red.png"}}, {{"uri", "textures/checker.webp"}}};
  quad.doc["textures"][0]["extensions"]["EXT_texture_webp"] = {{"source", 1}};
  quad.doc["extensionsUsed"] = {"EXT_texture_webp"};
  const Scene scene = load_gltf(quad.write("both"));
  const Scene png = load_gltf(kGltfData / "textured_quad.gltf");
  expect_same_texels(only_texture(scene), only_texture(png), 0.0f);
  EXPECT_EQ(only_texture(scene).name, "textures/checker.webp");
}

TEST(GltfTextureWebp, MissingWebpSourceNamesTheTexture) {
  QuadFixture quad;
  quad.doc["textures"][0]["extensions"]["EXT_texture_webp"] = {{"source", 5}};
  quad.doc["extensionsUsed"] = {"EXT_texture_webp"};
  EXPECT_THAT(load_error(quad.write("bad_webp")),
              HasSubstr("bad_webp.gltf: texture 0 EXT_texture_webp source 5 does not exist (1 images)"));
}

TEST(GltfTextureBasisu, CoreSourceFallbackLoadsWithAWarning) {
  QuadFixture quad;
  quad.add_ktx2("checker.ktx2");
  quad.doc["images"].push_back({{"uri", "checker.ktx2"}});
  quad.doc["textures"][0]["extensions"]["KHR_texture_basisu"] = {{"source", 1}};
  quad.doc["extensionsUsed"] = {"KHR_texture_basisu"};
  const Scene scene = load_gltf(quad.write("basisu"));
  const Scene png = load_gltf(kGltfData / "textured_quad.gltf");
  expect_same_texels(only_texture(scene), only_texture(png), 0.0f);
  EXPECT_TRUE(any_warning_has(scene, "texture 0: its KHR_texture_basisu (KTX2) image is not decoded (no Basis "
                                     "Universal transcoder): core source image 0 used"));
}

TEST(GltfTextureBasisu, WithoutACoreSourceTheLoadFailsNamingTheTexture) {
  QuadFixture quad;
  quad.add_ktx2("checker.ktx2");
  quad.doc["images"] = {{{"uri", "checker.ktx2"}}};
  quad.doc["textures"][0].erase("source");
  quad.doc["textures"][0]["name"] = "wood";
  quad.doc["textures"][0]["extensions"]["KHR_texture_basisu"] = {{"source", 0}};
  quad.doc["extensionsUsed"] = {"KHR_texture_basisu"};
  EXPECT_THAT(load_error(quad.write("basisu_only")),
              AllOf(HasSubstr("basisu_only.gltf: texture 0 'wood' (used by material 0 'checker' baseColorTexture)"),
                    HasSubstr("has only a KHR_texture_basisu (KTX2) image, which this loader cannot decode")));
}

TEST(GltfTextureBasisu, RequiredIsRefusedNamingTheExtension) {
  QuadFixture quad;
  quad.add_ktx2("checker.ktx2");
  quad.doc["images"].push_back({{"uri", "checker.ktx2"}});
  quad.doc["textures"][0]["extensions"]["KHR_texture_basisu"] = {{"source", 1}};
  quad.doc["extensionsUsed"] = {"KHR_texture_basisu"};
  quad.doc["extensionsRequired"] = {"KHR_texture_basisu"};
  EXPECT_THAT(load_error(quad.write("basisu_required")), HasSubstr("KHR_texture_basisu"));
}

}  // namespace
}  // namespace phyir::scenes
