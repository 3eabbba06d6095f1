#include "phyir/core/image_io.h"
#include "phyir/core/png_structure.h"

#include <OpenImageIO/filesystem.h>
#include <OpenImageIO/imageio.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <memory>

#include "phyir/core/atomic_file.h"
#include "phyir/core/error.h"

namespace phyir {

namespace fs = std::filesystem;
using OIIO::ImageInput;
using OIIO::ImageOutput;
using OIIO::ImageSpec;
using OIIO::TypeDesc;

namespace {

void check_has_pixels(const ImageSpec& spec, const std::string& what) {
  if (spec.width <= 0 || spec.height <= 0 || spec.nchannels <= 0) {
    fail("{}: image has no pixels ({}x{}, {} channels)", what, spec.width, spec.height,
         spec.nchannels);
  }
}

Image read_all(ImageInput& in, const std::string& what) {
  const ImageSpec& spec = in.spec();
  check_has_pixels(spec, what);
  Image image(spec.width, spec.height, spec.nchannels);
  if (!in.read_image(0, 0, 0, spec.nchannels, TypeDesc::FLOAT, image.pixels.data())) {
    fail("{}: cannot decode pixels: {}", what, in.geterror());
  }
  return image;
}

ByteImage read_all_codes(ImageInput& in, const std::string& what) {
  const ImageSpec& spec = in.spec();
  check_has_pixels(spec, what);
  ByteImage image{spec.width, spec.height, spec.nchannels, {}};
  image.codes.resize(static_cast<size_t>(spec.width) * spec.height * spec.nchannels);
  if (!in.read_image(0, 0, 0, spec.nchannels, TypeDesc::UINT8, image.codes.data())) {
    fail("{}: cannot decode pixels: {}", what, in.geterror());
  }
  return image;
}

// An in-memory image opened for reading. OIIO needs a format hint: sniff the magic numbers of
// the formats glTF allows (WebP through EXT_texture_webp: "RIFF", a size, "WEBP").
struct MemoryImageInput {
  OIIO::Filesystem::IOMemReader reader;
  std::unique_ptr<ImageInput> in;

  MemoryImageInput(const std::vector<unsigned char>& bytes, const std::string& what)
      : reader(bytes.data(), bytes.size()) {
    if (bytes.empty()) fail("{}: image data is empty", what);
    std::string ext = "png";
    if (bytes.size() >= 3 && bytes[0] == 0xFF && bytes[1] == 0xD8) ext = "jpg";
    if (bytes.size() >= 12 && std::memcmp(bytes.data(), "RIFF", 4) == 0 &&
        std::memcmp(bytes.data() + 8, "WEBP", 4) == 0)
      ext = "webp";
    if (ext == "png") {
      const std::string problem = png_structure_error(bytes.data(), bytes.size());
      if (!problem.empty()) fail("{}: cannot decode image: {}", what, problem);
    }
    in = ImageInput::open("in-memory." + ext, nullptr, &reader);
    if (!in) fail("{}: cannot decode image: {}", what, OIIO::geterror());
  }
};

std::vector<std::string> default_channel_names(int channels) {
  switch (channels) {
    case 1: return {"Y"};
    case 2: return {"Y", "A"};
    case 3: return {"R", "G", "B"};
    case 4: return {"R", "G", "B", "A"};
    default: {
      std::vector<std::string> names;
      for (int c = 0; c < channels; ++c) names.push_back("C" + std::to_string(c));
      return names;
    }
  }
}

}  // namespace

Image read_image(const fs::path& path) {
  if (!fs::exists(path)) fail("{}: image file not found", path.string());
  auto in = ImageInput::open(path.string());
  if (!in) fail("{}: cannot open image: {}", path.string(), OIIO::geterror());
  return read_all(*in, path.string());
}

Image read_image_from_memory(const std::vector<unsigned char>& bytes, const std::string& what) {
  MemoryImageInput input(bytes, what);
  return read_all(*input.in, what);
}

std::variant<ByteImage, Image> read_image_from_memory_at_file_depth(const std::vector<unsigned char>& bytes,
                                                                    const std::string& what) {
  MemoryImageInput input(bytes, what);
  if (input.in->spec().format == TypeDesc::UINT8) return read_all_codes(*input.in, what);
  return read_all(*input.in, what);
}

namespace {

// An 8-bit file's value: clamped to [0, 1], non-finite as 0.
float display_value(float v) { return std::isfinite(v) ? std::clamp(v, 0.0f, 1.0f) : 0.0f; }

}  // namespace

void write_image(const fs::path& path, const Image& image,
                 const std::vector<std::string>& channel_names) {
  if (image.empty()) fail("{}: refusing to write an empty image", path.string());
  if (!path.parent_path().empty()) fs::create_directories(path.parent_path());
  const std::string ext = path.extension().string();
  const bool hdr = ext == ".exr" || ext == ".hdr";
  const fs::path tmp = temporary_sibling(path);
  auto out = ImageOutput::create(tmp.string());
  if (!out) fail("{}: no image writer for this extension: {}", path.string(), OIIO::geterror());
  ImageSpec spec(image.width, image.height, image.channels, hdr ? TypeDesc::FLOAT : TypeDesc::UINT8);
  spec.channelnames = channel_names.empty() ? default_channel_names(image.channels) : channel_names;
  if (ext == ".exr") spec.attribute("compression", "zip");
  // A fixed timestamp: the same render must give byte-identical files (OpenEXR and PNG
  // writers stamp the current time otherwise).
  spec.attribute("DateTime", "1970:01:01 00:00:00");
  if (!out->open(tmp.string(), spec)) fail("{}: cannot open for writing: {}", path.string(), out->geterror());
  bool ok;
  if (hdr) {
    ok = out->write_image(TypeDesc::FLOAT, image.pixels.data());
  } else {
    std::vector<float> clamped(image.pixels.size());
    std::transform(image.pixels.begin(), image.pixels.end(), clamped.begin(), display_value);
    ok = out->write_image(TypeDesc::FLOAT, clamped.data());
  }
  if (!ok || !out->close()) {
    std::error_code ec;
    fs::remove(tmp, ec);
    fail("{}: write failed: {}", path.string(), out->geterror());
  }
  commit_file(tmp, path);
}

void write_animation(const fs::path& path, const std::vector<Image>& frames, float fps) {
  if (frames.empty()) fail("{}: an animation needs at least one frame", path.string());
  for (const Image& f : frames)
    if (f.width != frames[0].width || f.height != frames[0].height || f.channels < 3)
      fail("{}: animation frames must be RGB and of one size", path.string());
  if (!path.parent_path().empty()) fs::create_directories(path.parent_path());
  const fs::path tmp = temporary_sibling(path);
  auto out = ImageOutput::create(tmp.string());
  if (!out || !out->supports("multiimage") || !out->supports("appendsubimage"))
    fail("{}: this format cannot hold an animation", path.string());
  ImageSpec spec(frames[0].width, frames[0].height, 3, TypeDesc::UINT8);
  spec.attribute("FramesPerSecond", TypeDesc::TypeRational, std::vector<int>{int(std::lround(fps * 100)), 100}.data());
  spec.attribute("gif:LoopCount", 0);
  const std::vector<ImageSpec> specs(frames.size(), spec);
  bool ok = out->open(tmp.string(), int(specs.size()), specs.data());
  std::vector<float> rgb(size_t(spec.width) * size_t(spec.height) * 3);
  for (size_t k = 0; ok && k < frames.size(); ++k) {
    const Image& f = frames[k];
    for (size_t i = 0; i < rgb.size() / 3; ++i)
      for (int c = 0; c < 3; ++c) {
        rgb[i * 3 + size_t(c)] = display_value(f.pixels[i * size_t(f.channels) + size_t(c)]);
      }
    ok = (k == 0 || out->open(tmp.string(), spec, ImageOutput::AppendSubimage)) &&
         out->write_image(TypeDesc::FLOAT, rgb.data());
  }
  if (!ok || !out->close()) {
    std::error_code ec;
    fs::remove(tmp, ec);
    fail("{}: write failed: {}", path.string(), out->geterror());
  }
  commit_file(tmp, path);
}

}  // namespace phyir
