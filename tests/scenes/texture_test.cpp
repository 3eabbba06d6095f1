// Texture decoding through OpenImageIO, the sRGB decode of colour textures (and not of data
// textures), one entry per use, sampler state, and Texture::sample's wrap modes.
#include <gtest/gtest.h>

#include <cmath>

#include "gltf_test_helpers.h"
#include "phyir/core/atomic_file.h"
#include "phyir/core/image_io.h"
#include "phyir/scenes/gltf_loader.h"

namespace phyir::scenes {
namespace {

using nlohmann::json;
using test::GltfBuilder;

// IEC 61966-2-1 sRGB decoding, the reference the OCIO path must reproduce.
float srgb_decode(float c) { return c <= 0.04045f ? c / 12.92f : std::pow((c + 0.055f) / 1.055f, 2.4f); }

// 8-bit code values of a 2x1 test image: left texel, right texel.
const float kLeft[3] = {128.0f / 255.0f, 64.0f / 255.0f, 1.0f};
const float kRight[3] = {0.0f, 1.0f, 10.0f / 255.0f};

// A triangle whose material uses texture 0 (the 2x1 image, with `sampler`) as base colour,
// metallic-roughness and emissive.
Scene load_textured(const json& sampler, bool glb = false) {
  const std::filesystem::path dir = test::fresh_test_dir();
  Image image(2, 1, 3);
  for (int c = 0; c < 3; ++c) {
    image.at(0, 0, c) = kLeft[c];
    image.at(1, 0, c) = kRight[c];
  }
  write_image(dir / "two_texels.png", image);
  GltfBuilder b;
  b.add_triangles("tri", test::unit_triangle(), {0, 1, 2}, {}, {{"material", 0}});
  b.doc["materials"] = {
      {{"pbrMetallicRoughness",
        {{"baseColorTexture", {{"index", 0}}}, {"metallicRoughnessTexture", {{"index", 0}}}}},
       {"emissiveTexture", {{"index", 0}}}}};
  if (glb) {
    // The image inside the binary buffer instead of a file.
    const std::string png = read_file(dir / "two_texels.png");
    b.doc["images"] = {{{"bufferView", b.add_view(png.data(), png.size())}, {"mimeType", "image/png"}}};
  } else {
    b.doc["images"] = {{{"uri", "two_texels.png"}}};
  }
  b.doc["textures"] = {{{"source", 0}, {"sampler", 0}}};
  b.doc["samplers"] = json::array({sampler});  // not {sampler}: clang reads that as a copy (CWG 2137)
  b.set_scene({b.add_node({{"mesh", 0}})});
  return load_gltf(glb ? b.write_glb(dir, "textured") : b.write_gltf(dir, "textured"));
}

TEST(GltfTextures, ColourIsSrgbDecodedDataStaysLinear) {
  const Scene scene = load_textured(json::object());
  const Material& m = scene.materials[0];
  // Same image as colour (twice) and as data: one decoded and one linear entry.
  ASSERT_EQ(scene.textures.size(), 2u);
  EXPECT_EQ(m.base_color_texture.texture, m.emissive_texture.texture);
  const Texture& colour = scene.textures[static_cast<size_t>(m.base_color_texture.texture)];
  const Texture& data = scene.textures[static_cast<size_t>(m.metallic_roughness_texture.texture)];
  EXPECT_EQ(colour.encoding, TextureEncoding::SrgbColour);
  EXPECT_EQ(data.encoding, TextureEncoding::LinearData);
  ASSERT_EQ(colour.width(), 2);
  ASSERT_EQ(colour.height(), 1);
  for (int c = 0; c < 3; ++c) {
    EXPECT_NEAR(colour.texel(0, 0)[c], srgb_decode(kLeft[c]), 2e-3f) << "channel " << c;
    EXPECT_NEAR(colour.texel(1, 0)[c], srgb_decode(kRight[c]), 2e-3f) << "channel " << c;
    EXPECT_NEAR(data.texel(0, 0)[c], kLeft[c], 1e-6f);
    EXPECT_NEAR(data.texel(1, 0)[c], kRight[c], 1e-6f);
  }
  EXPECT_EQ(colour.texel(0, 0).w, 1.0f);  // RGB images are opaque
}

TEST(GltfTextures, ImageInsideGlbBufferView) {
  const Scene scene = load_textured(json::object(), /*glb=*/true);
  const Texture& data =
      scene.textures[static_cast<size_t>(scene.materials[0].metallic_roughness_texture.texture)];
  ASSERT_EQ(data.texel_count(), 2u);
  EXPECT_NEAR(data.texel(0, 0).x, kLeft[0], 1e-6f);
  EXPECT_NEAR(data.texel(1, 0).y, kRight[1], 1e-6f);
}

TEST(GltfTextures, SamplerWrapModesAndNearestMagFilter) {
  const Scene scene = load_textured({{"wrapS", 33071}, {"wrapT", 33648}, {"magFilter", 9728}});
  for (const Texture& t : scene.textures) {
    EXPECT_EQ(t.wrap_s, WrapMode::ClampToEdge);
    EXPECT_EQ(t.wrap_t, WrapMode::MirroredRepeat);
    EXPECT_TRUE(t.nearest);
  }
  const Scene defaults = load_textured(json::object());
  EXPECT_EQ(defaults.textures[0].wrap_s, WrapMode::Repeat);
  EXPECT_FALSE(defaults.textures[0].nearest);
}

TEST(GltfTextures, HandWrittenFixtureWithExternalFilesRelativeToTheGltf) {
  // Loaded through a relative path so that the .bin and the image are found from the
  // .gltf's folder, not from the working directory.
  const std::filesystem::path fixture =
      std::filesystem::path(PHYIR_TEST_DATA_DIR) / "gltf" / "textured_quad.gltf";
  const Scene scene = load_gltf(std::filesystem::relative(fixture));
  ASSERT_EQ(scene.meshes.size(), 1u);
  EXPECT_EQ(scene.meshes[0].texcoords0[0], glm::vec2(0, 1));
  ASSERT_EQ(scene.textures.size(), 1u);
  const Texture& checker = scene.textures[0];
  EXPECT_EQ(checker.name, "textures/checker.png");
  EXPECT_TRUE(checker.nearest);
  ASSERT_EQ(checker.texel_count(), 4u);
  EXPECT_NEAR(checker.texel(0, 0).x, 1.0f, 1e-4f);  // white stays white through the sRGB decode
  EXPECT_NEAR(checker.texel(1, 0).x, 0.0f, 1e-6f);
  EXPECT_EQ(scene.materials[0].name, "checker");
  EXPECT_EQ(scene.materials[0].metallic_factor, 0.0f);
}

Texture two_texel_texture(WrapMode wrap) {
  Texture t = Texture::from_linear(2, 1, {glm::vec4(0.0f), glm::vec4(1.0f)});
  t.wrap_s = t.wrap_t = wrap;
  t.nearest = true;
  return t;
}

TEST(TextureSample, WrapModes) {
  const Texture repeat = two_texel_texture(WrapMode::Repeat);
  EXPECT_EQ(repeat.sample({1.25f, 0.5f}), repeat.sample({0.25f, 0.5f}));
  EXPECT_EQ(repeat.sample({-0.25f, 0.5f}).x, 1.0f);
  const Texture clamp = two_texel_texture(WrapMode::ClampToEdge);
  EXPECT_EQ(clamp.sample({1.75f, 0.5f}).x, 1.0f);
  EXPECT_EQ(clamp.sample({-3.0f, 0.5f}).x, 0.0f);
  const Texture mirror = two_texel_texture(WrapMode::MirroredRepeat);
  EXPECT_EQ(mirror.sample({1.25f, 0.5f}).x, 1.0f);  // mirrored: texel 1 sits at u in [1, 1.5)
}

}  // namespace
}  // namespace phyir::scenes
