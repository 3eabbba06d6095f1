// Compact texel storage: 8-bit images keep their codes (level 0 reads exactly what decoding
// the image as float, then through OpenColorIO, gives), mip levels are filtered on linear
// values and stay within a code of the float pyramid, 16-bit images are stored as half,
// memory per texel is what the format says, and the parallel decode gives the same textures
// (and the same first error) whatever the number of threads.
#define IMATH_HALF_NO_LOOKUP_TABLE  // header-only half conversions: the test does not link Imath
#include <Imath/half.h>
#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <tbb/global_control.h>

#include <cmath>
#include <cstring>

#include "gltf_test_helpers.h"
#include "phyir/core/atomic_file.h"
#include "phyir/core/colour.h"
#include "phyir/core/error.h"
#include "phyir/core/image_io.h"
#include "phyir/scenes/gltf_loader.h"

namespace phyir::scenes {
namespace {

namespace fs = std::filesystem;
using test::GltfBuilder;

// A triangle per image file in `dir`, material i showing image i as base colour (sRGB) and
// as metallic-roughness (linear data): Scene textures 2i (colour) and 2i + 1 (data).
fs::path write_scene(const fs::path& dir, const std::vector<std::string>& image_files) {
  GltfBuilder b;
  std::vector<int> nodes;
  for (size_t i = 0; i < image_files.size(); ++i) {
    const int index = static_cast<int>(i);
    b.doc["images"].push_back({{"uri", image_files[i]}});
    b.doc["textures"].push_back({{"source", index}});
    b.doc["materials"].push_back({{"pbrMetallicRoughness",
                                   {{"baseColorTexture", {{"index", index}}},
                                    {"metallicRoughnessTexture", {{"index", index}}}}}});
    b.add_triangles("tri" + std::to_string(i), test::unit_triangle(), {0, 1, 2}, {}, {{"material", index}});
    nodes.push_back(b.add_node({{"mesh", index}}));
  }
  b.set_scene(nodes);
  return b.write_gltf(dir, "textures");
}

const Texture& colour_of(const Scene& scene, size_t material) {
  return scene.textures.at(static_cast<size_t>(scene.materials.at(material).base_color_texture.texture));
}

const Texture& data_of(const Scene& scene, size_t material) {
  return scene.textures.at(static_cast<size_t>(scene.materials.at(material).metallic_roughness_texture.texture));
}

// What the loader stored before texels were compact: the image decoded as float by
// OpenImageIO, sRGB-decoded by OpenColorIO for colour, expanded to RGBA.
std::vector<glm::vec4> float_decode(const fs::path& file, bool colour) {
  const std::string bytes = read_file(file);
  Image image = read_image_from_memory(std::vector<unsigned char>(bytes.begin(), bytes.end()), file.string());
  if (colour) srgb_to_linear(image);
  std::vector<glm::vec4> texels;
  for (int y = 0; y < image.height; ++y)
    for (int x = 0; x < image.width; ++x) {
      const int c = image.channels;
      const float r = image.at(x, y, 0), a = c == 2 || c == 4 ? image.at(x, y, c - 1) : 1.0f;
      texels.push_back(c >= 3 ? glm::vec4(r, image.at(x, y, 1), image.at(x, y, 2), a) : glm::vec4(r, r, r, a));
    }
  return texels;
}

// Every texel of `level`, row-major.
std::vector<glm::vec4> level_texels(const Texture& t, int level) {
  std::vector<glm::vec4> texels;
  for (int y = 0; y < t.level_height(level); ++y)
    for (int x = 0; x < t.level_width(level); ++x) texels.push_back(t.texel(x, y, level));
  return texels;
}

bool same_bits(const glm::vec4& a, const glm::vec4& b) { return std::memcmp(&a, &b, sizeof a) == 0; }

// An 8-bit image holding every code in every channel, `channels` of them (32 x 8 texels).
void write_all_codes(const fs::path& path, int channels) {
  Image image(32, 8, channels);
  for (int i = 0; i < 256; ++i)
    for (int c = 0; c < channels; ++c) {
      const int code = c == 0 ? i : c == 1 ? (i * 7 + 3) % 256 : c == 2 ? 255 - i : (i * 13) % 256;
      image.at(i % 32, i / 32, c) = float(code) / 255.0f;
    }
  write_image(path, image, channels == 2 ? std::vector<std::string>{"Y", "A"} : std::vector<std::string>{});
}

TEST(TextureStorage, EightBitLevelZeroIsBitIdenticalToTheFloatDecode) {
  const fs::path dir = test::fresh_test_dir();
  write_all_codes(dir / "rgba.png", 4);
  write_all_codes(dir / "rgb.png", 3);
  write_all_codes(dir / "grey_alpha.png", 2);
  write_all_codes(dir / "rgb.jpg", 3);
  const std::vector<std::string> files = {"rgba.png", "rgb.png", "grey_alpha.png", "rgb.jpg"};
  const Scene scene = load_gltf(write_scene(dir, files));
  for (size_t i = 0; i < files.size(); ++i) {
    const Texture& colour = colour_of(scene, i);
    const Texture& data = data_of(scene, i);
    EXPECT_EQ(colour.format(), TexelFormat::Srgb8) << files[i];
    EXPECT_EQ(data.format(), TexelFormat::Unorm8) << files[i];
    const std::vector<glm::vec4> want_colour = float_decode(dir / files[i], true);
    const std::vector<glm::vec4> want_data = float_decode(dir / files[i], false);
    const std::vector<glm::vec4> got_colour = level_texels(colour, 0), got_data = level_texels(data, 0);
    ASSERT_EQ(got_colour.size(), want_colour.size()) << files[i];
    for (size_t t = 0; t < want_colour.size(); ++t) {
      EXPECT_TRUE(same_bits(got_colour[t], want_colour[t])) << files[i] << " colour texel " << t;
      EXPECT_TRUE(same_bits(got_data[t], want_data[t])) << files[i] << " data texel " << t;
    }
  }
}

TEST(TextureStorage, EightBitMipLevelsStayWithinACodeOfTheFloatPyramid) {
  // A black-and-white checker with noise: filtering the sRGB codes instead of linear values
  // would put the level means near 0.21 instead of 0.5.
  const fs::path dir = test::fresh_test_dir();
  Image image(64, 32, 3);
  uint32_t state = 12345;
  for (int y = 0; y < image.height; ++y)
    for (int x = 0; x < image.width; ++x)
      for (int c = 0; c < 3; ++c) {
        state = state * 1664525u + 1013904223u;
        const int noise = int(state >> 28);  // 0-15
        image.at(x, y, c) = float((x + y) % 2 ? 255 - noise : noise) / 255.0f;
      }
  write_image(dir / "checker.png", image);
  const Scene scene = load_gltf(write_scene(dir, {"checker.png"}));
  for (const Texture* stored : {&colour_of(scene, 0), &data_of(scene, 0)}) {
    Texture exact = Texture::from_linear(stored->width(), stored->height(), level_texels(*stored, 0));
    exact.build_mips();
    ASSERT_EQ(stored->levels(), 7);  // 64x32 ... 1x1
    ASSERT_EQ(exact.levels(), stored->levels());
    for (int level = 1; level < stored->levels(); ++level) {
      const std::vector<glm::vec4> got = level_texels(*stored, level), want = level_texels(exact, level);
      glm::dvec4 got_mean(0.0), want_mean(0.0);
      for (size_t t = 0; t < got.size(); ++t) {
        got_mean += glm::dvec4(got[t]) / double(got.size());
        want_mean += glm::dvec4(want[t]) / double(want.size());
        // Each stored texel is the nearest code: within half the widest step of the sRGB
        // decode (at code 255, 0.0093) of the float value.
        for (int c = 0; c < 4; ++c) EXPECT_NEAR(got[t][c], want[t][c], 0.0047f) << "level " << level << " texel " << t;
      }
      for (int c = 0; c < 4; ++c) EXPECT_NEAR(got_mean[c], want_mean[c], 1.0 / 255.0) << "level " << level;
      if (stored->encoding == TextureEncoding::LinearData) {
        EXPECT_NEAR(got_mean.x, 0.5, 0.03) << "level " << level;
      }
    }
  }
}

float through_half(float v) { return imath_half_to_float(imath_float_to_half(v)); }

TEST(TextureStorage, SixteenBitImagesAreStoredAsHalf) {
  // rgba16.png: 4 x 2, 16-bit RGBA; texel (1, 0) is (1, 32768, 65535, 65535) / 65535.
  const fs::path file = fs::path(PHYIR_TEST_DATA_DIR) / "gltf" / "textures" / "rgba16.png";
  const fs::path dir = test::fresh_test_dir();
  fs::copy_file(file, dir / "rgba16.png");
  const Scene scene = load_gltf(write_scene(dir, {"rgba16.png"}));
  const Texture& colour = colour_of(scene, 0);
  const Texture& data = data_of(scene, 0);
  EXPECT_EQ(colour.format(), TexelFormat::Half);
  EXPECT_EQ(data.format(), TexelFormat::Half);
  // 32768 / 65535 = 0.5000076 in float; half's step at 0.5 is 2^-11.
  EXPECT_EQ(data.texel(1, 0).y, 0.5f);
  const std::vector<glm::vec4> want_colour = float_decode(file, true), want_data = float_decode(file, false);
  const std::vector<glm::vec4> got_colour = level_texels(colour, 0), got_data = level_texels(data, 0);
  ASSERT_EQ(got_data.size(), 8u);
  for (size_t t = 0; t < 8; ++t)
    for (int c = 0; c < 4; ++c) {
      EXPECT_EQ(got_colour[t][c], through_half(want_colour[t][c])) << "colour texel " << t << " channel " << c;
      EXPECT_EQ(got_data[t][c], through_half(want_data[t][c])) << "data texel " << t << " channel " << c;
    }
  EXPECT_EQ(data.bytes(), 8u * (8 + 2 + 1));  // 4x2, 2x1, 1x1 at 8 bytes a texel
}

TEST(TextureStorage, BytesPerTexelFollowTheFormat) {
  const fs::path dir = test::fresh_test_dir();
  write_all_codes(dir / "rgb.png", 3);  // 32 x 8
  const Scene scene = load_gltf(write_scene(dir, {"rgb.png"}));
  const Texture& colour = colour_of(scene, 0);
  ASSERT_EQ(colour.levels(), 6);  // 32x8, 16x4, 8x2, 4x1, 2x1, 1x1
  const size_t texels = 256 + 64 + 16 + 4 + 2 + 1;
  EXPECT_EQ(colour.bytes(), 4 * texels);  // RGBA8: 4 bytes a texel, a third more for the mips
  EXPECT_LE(colour.bytes(), 4 * 256 * 4 / 3 + 4 * 6);
  EXPECT_EQ(data_of(scene, 0).bytes(), 4 * texels);

  const std::vector<glm::vec4> two = {glm::vec4(0.25f), glm::vec4(0.75f)};
  EXPECT_EQ(Texture::from_linear(2, 1, two).bytes(), 32u);
  EXPECT_EQ(Texture::from_linear(2, 1, two, TexelFormat::Half).bytes(), 16u);
  EXPECT_EQ(Texture::from_linear(2, 1, two, TexelFormat::Srgb8).bytes(), 8u);
  EXPECT_EQ(Texture().bytes(), 0u);
}

TEST(TextureStorage, EncodingLinearValuesPicksTheNearestCode) {
  // The decoded value of every code encodes back to that code, in both 8-bit formats.
  const Texture codes = Texture::from_codes(256, 1, [] {
    std::vector<uint8_t> rgba;
    for (int i = 0; i < 256; ++i) rgba.insert(rgba.end(), {uint8_t(i), uint8_t(i), uint8_t(i), uint8_t(i)});
    return rgba;
  }(), TexelFormat::Srgb8);
  const std::vector<glm::vec4> table = level_texels(codes, 0);
  const Texture again = Texture::from_linear(256, 1, table, TexelFormat::Srgb8);
  for (int i = 0; i < 256; ++i) EXPECT_TRUE(same_bits(again.texel(i, 0), codes.texel(i, 0))) << "code " << i;
  // Values between codes: the nearest (ties to the lower code), as a search of every code finds it.
  std::vector<glm::vec4> values;
  for (int i = 0; i <= 20000; ++i) values.push_back(glm::vec4(float(i) / 20000.0f));
  const Texture encoded = Texture::from_linear(int(values.size()), 1, values, TexelFormat::Srgb8);
  for (size_t i = 0; i < values.size(); ++i) {
    size_t best = 0;
    for (size_t code = 1; code < 256; ++code)
      if (std::abs(table[code].x - values[i].x) < std::abs(table[best].x - values[i].x)) best = code;
    ASSERT_EQ(encoded.texel(int(i), 0).x, table[best].x) << "value " << values[i].x;
  }
  const glm::vec4 unorm =
      Texture::from_linear(1, 1, {glm::vec4(0.6f, -1.0f, 2.0f, NAN)}, TexelFormat::Unorm8).texel(0, 0);
  const glm::vec4 want(153.0f / 255.0f, 0.0f, 1.0f, 0.0f);  // clamped, NaN to 0
  for (int c = 0; c < 4; ++c) EXPECT_NEAR(unorm[c], want[c], 1e-7f) << "channel " << c;
  EXPECT_THROW(Texture::from_linear(2, 2, {glm::vec4(0.0f)}), Error);
}

// Texture 0 is a large image (slow to decode); the images of textures 1 and of the second half
// are broken (quick to fail). The first error in texture order names image 1.
struct ManyTextures {
  fs::path dir = test::fresh_test_dir();
  std::vector<std::string> files;

  explicit ManyTextures(bool broken) {
    Image big(512, 512, 3);
    for (size_t i = 0; i < big.pixels.size(); ++i) big.pixels[i] = float((i * 2654435761u) % 251) / 255.0f;
    write_image(dir / "big.png", big);
    files.push_back("big.png");
    for (int i = 1; i < 24; ++i) {
      const std::string name = "t" + std::to_string(i) + ".png";
      Image image(16 + i, 8, 3);
      for (size_t p = 0; p < image.pixels.size(); ++p) image.pixels[p] = float((p * 31 + i) % 256) / 255.0f;
      write_image(dir / name, image);
      if (broken && (i == 1 || i >= 12)) {
        std::string bytes = read_file(dir / name);
        bytes.resize(bytes.size() / 2);
        test::write_bytes(dir / name, bytes.data(), bytes.size());
      }
      files.push_back(name);
    }
    files.push_back("rgba16.png");  // and a half texture
    fs::copy_file(fs::path(PHYIR_TEST_DATA_DIR) / "gltf" / "textures" / "rgba16.png", dir / "rgba16.png");
  }
};

Scene load_with_threads(const fs::path& file, int threads) {
  const tbb::global_control limit(tbb::global_control::max_allowed_parallelism, static_cast<size_t>(threads));
  return load_gltf(file);
}

TEST(TextureStorage, ParallelDecodeGivesTheSameTexturesAsSerial) {
  ManyTextures many(false);
  const fs::path file = write_scene(many.dir, many.files);
  const Scene serial = load_with_threads(file, 1);
  const Scene parallel = load_with_threads(file, 4);
  ASSERT_EQ(serial.textures.size(), 2 * many.files.size());
  ASSERT_EQ(parallel.textures.size(), serial.textures.size());
  for (size_t i = 0; i < serial.textures.size(); ++i) {
    const Texture &a = serial.textures[i], &b = parallel.textures[i];
    EXPECT_EQ(a.name, b.name);
    ASSERT_EQ(a.format(), b.format()) << a.name;
    ASSERT_EQ(a.levels(), b.levels()) << a.name;
    EXPECT_EQ(a.bytes(), b.bytes()) << a.name;
    for (int level = 0; level < a.levels(); ++level) {
      const std::vector<glm::vec4> ta = level_texels(a, level), tb = level_texels(b, level);
      ASSERT_EQ(ta.size(), tb.size());
      EXPECT_EQ(std::memcmp(ta.data(), tb.data(), ta.size() * sizeof(glm::vec4)), 0) << a.name << " level " << level;
    }
  }
}

TEST(TextureStorage, FirstBrokenImageInTextureOrderIsTheErrorWhateverTheThreads) {
  ManyTextures many(true);
  const fs::path file = write_scene(many.dir, many.files);
  for (int threads : {1, 2, 4}) {
    for (int run = 0; run < 3; ++run) {
      try {
        load_with_threads(file, threads);
        ADD_FAILURE() << "loaded with broken images";
      } catch (const Error& e) {
        EXPECT_THAT(e.what(), ::testing::HasSubstr("image 1: cannot decode")) << threads << " threads";
      }
    }
  }
}

}  // namespace
}  // namespace phyir::scenes
