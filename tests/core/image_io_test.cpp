// Image files through OpenImageIO: lossless EXR round trip, atomic writes, clear errors.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <iterator>

#include "phyir/core/error.h"
#include "phyir/core/image_io.h"
#include "phyir/core/png_structure.h"

#include <OpenImageIO/imageio.h>

namespace fs = std::filesystem;
using phyir::Image;

namespace {

fs::path scratch_dir(const std::string& name) {
  const fs::path dir = fs::temp_directory_path() / ("phyir_core_test_" + name);
  fs::remove_all(dir);
  fs::create_directories(dir);
  return dir;
}

}  // namespace

TEST(ImageIo, ExrRoundTripIsBitExact) {
  const fs::path dir = scratch_dir("exr");
  Image image(7, 5, 3);
  for (size_t i = 0; i < image.pixels.size(); ++i) image.pixels[i] = float(i) * 0.37f - 3.0f + 1e-7f * i;
  image.pixels[4] = 65504.0f * 8.0f;  // beyond half range: must survive as float
  phyir::write_image(dir / "a.exr", image);
  const Image back = phyir::read_image(dir / "a.exr");
  ASSERT_EQ(back.width, 7);
  ASSERT_EQ(back.height, 5);
  ASSERT_EQ(back.channels, 3);
  EXPECT_EQ(back.pixels, image.pixels);
}

TEST(ImageIo, SingleChannelExrKeepsOneChannel) {
  const fs::path dir = scratch_dir("mono");
  Image image(4, 2, 1, 2.5f);
  phyir::write_image(dir / "depth.exr", image);
  const Image back = phyir::read_image(dir / "depth.exr");
  EXPECT_EQ(back.channels, 1);
  EXPECT_EQ(back.pixels, image.pixels);
}

TEST(ImageIo, PngQuantisesAndClamps) {
  const fs::path dir = scratch_dir("png");
  Image image(2, 1, 3);
  image.pixels = {0.0f, 0.5f, 1.0f, 2.0f, -1.0f, 0.25f};
  phyir::write_image(dir / "a.png", image);
  const Image back = phyir::read_image(dir / "a.png");
  ASSERT_EQ(back.pixels.size(), 6u);
  EXPECT_NEAR(back.pixels[1], 0.5f, 1.0f / 255.0f);
  EXPECT_FLOAT_EQ(back.pixels[3], 1.0f);  // clamped from 2
  EXPECT_FLOAT_EQ(back.pixels[4], 0.0f);  // clamped from -1
}

TEST(ImageIo, WriteLeavesNoTemporaryFiles) {
  const fs::path dir = scratch_dir("atomic");
  phyir::write_image(dir / "x.exr", Image(3, 3, 3, 1.0f));
  int files = 0;
  for (const auto& entry : fs::directory_iterator(dir)) {
    ++files;
    EXPECT_EQ(entry.path().filename(), "x.exr");
  }
  EXPECT_EQ(files, 1);
}

// Three frames, red, green, blue: a GIF of three images in that order, and no temporary file.
TEST(ImageIo, AnimationHoldsEveryFrameInOrder) {
  const fs::path dir = scratch_dir("gif");
  std::vector<Image> frames;
  for (int k = 0; k < 3; ++k) {
    Image f(8, 4, 3, 0.0f);
    for (size_t i = 0; i < f.pixels.size(); i += 3) f.pixels[i + size_t(k)] = 1.0f;
    frames.push_back(f);
  }
  phyir::write_animation(dir / "path.gif", frames, 4.0f);
  auto in = OIIO::ImageInput::open((dir / "path.gif").string());
  ASSERT_TRUE(in);
  int subimages = 0;
  while (in->seek_subimage(subimages, 0)) {
    std::vector<float> rgb(size_t(in->spec().width) * size_t(in->spec().height) * size_t(in->spec().nchannels));
    ASSERT_TRUE(in->read_image(subimages, 0, 0, in->spec().nchannels, OIIO::TypeDesc::FLOAT, rgb.data()));
    for (int c = 0; c < 3; ++c) EXPECT_NEAR(rgb[size_t(c)], c == subimages ? 1.0f : 0.0f, 0.01f) << subimages;
    ++subimages;
  }
  EXPECT_EQ(subimages, 3);
  EXPECT_EQ(std::distance(fs::directory_iterator(dir), fs::directory_iterator()), 1);
  EXPECT_THROW(phyir::write_animation(dir / "bad.gif", {frames[0], Image(4, 4, 3)}, 4.0f), phyir::Error);
}

TEST(ImageIo, MissingFileNamesThePath) {
  try {
    phyir::read_image("/nonexistent/dir/missing.exr");
    FAIL() << "expected phyir::Error";
  } catch (const phyir::Error& e) {
    EXPECT_THAT(e.what(), testing::HasSubstr("missing.exr"));
    EXPECT_THAT(e.what(), testing::HasSubstr("not found"));
  }
}

TEST(ImageIo, CorruptFileIsAnErrorNotACrash) {
  const fs::path dir = scratch_dir("corrupt");
  {
    std::ofstream out(dir / "bad.png", std::ios::binary);
    out << "\x89PNG\r\n\x1a\n this is not a png";
  }
  EXPECT_THROW(phyir::read_image(dir / "bad.png"), phyir::Error);
}

TEST(ImageIo, DecodesFromMemory) {
  const fs::path dir = scratch_dir("memory");
  Image image(3, 2, 4, 0.0f);
  image.at(1, 1, 0) = 1.0f;
  image.at(1, 1, 3) = 1.0f;
  phyir::write_image(dir / "m.png", image);
  const std::string bytes = [&] {
    std::ifstream in(dir / "m.png", std::ios::binary);
    return std::string(std::istreambuf_iterator<char>(in), {});
  }();
  const Image back = phyir::read_image_from_memory(std::vector<unsigned char>(bytes.begin(), bytes.end()), "test");
  ASSERT_EQ(back.width, 3);
  EXPECT_FLOAT_EQ(back.at(1, 1, 0), 1.0f);
  EXPECT_FLOAT_EQ(back.at(0, 0, 0), 0.0f);
}

// A PNG cut anywhere, or with a chunk length past its end, is refused with a message that
// says so before any decoder reads it (OIIO 2.4 leaks an error string when libpng hits the
// end of in-memory data: scripts/fuzz.sh found it); the whole file still decodes.
TEST(ImageIo, TruncatedPngInMemoryIsRefusedBeforeDecoding) {
  const fs::path dir = scratch_dir("truncated");
  Image image(8, 8, 3, 0.5f);
  phyir::write_image(dir / "t.png", image);
  std::ifstream in(dir / "t.png", std::ios::binary);
  const std::vector<unsigned char> bytes((std::istreambuf_iterator<char>(in)), {});
  EXPECT_EQ(phyir::png_structure_error(bytes.data(), bytes.size()), "");
  for (size_t cut = 0; cut < bytes.size(); ++cut) {
    const std::vector<unsigned char> part(bytes.begin(), bytes.begin() + long(cut));
    try {
      phyir::read_image_from_memory(part, "texture 3");
      ADD_FAILURE() << "a PNG cut at byte " << cut << " decoded";
    } catch (const phyir::Error& e) {
      const std::string message = e.what();
      EXPECT_NE(message.find("texture 3"), std::string::npos) << message;
      if (cut >= 8) {
        EXPECT_NE(message.find("truncated"), std::string::npos) << message;
      }
    }
  }
  std::vector<unsigned char> lying = bytes;
  lying[8] = 0x7F;  // the first chunk (IHDR) now declares ~2 GB
  EXPECT_NE(phyir::png_structure_error(lying.data(), lying.size()).find("truncated in chunk 0 (IHDR"), std::string::npos);
}
