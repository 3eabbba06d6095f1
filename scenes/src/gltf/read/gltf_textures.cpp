#include "gltf/read/gltf_textures.h"

#include <OpenImageIO/filesystem.h>
#include <OpenImageIO/imageio.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstring>
#include <exception>
#include <variant>

#include "gltf/read/gltf_values.h"
#include "phyir/core/colour.h"
#include "phyir/core/image_io.h"
#include "phyir/core/png_structure.h"

namespace phyir::scenes::gltf {

namespace {

// Decoded textures are float RGBA-or-fewer: at most 2^28 values (1 GiB), e.g. 8192 x 8192
// RGBA or 16384 x 16384 grey. A PNG header may claim 1,000,000 x 1,000,000 pixels in a few
// bytes; the limit is checked on the header, before anything is allocated.
constexpr uint64_t kMaxTextureValues = uint64_t{1} << 28;

constexpr const char* kWebp = "EXT_texture_webp";
constexpr const char* kBasisu = "KHR_texture_basisu";

// Width, height and channels from the encoded image's header (nothing decoded), or zeros when
// OIIO cannot open it (the decoder then reports why). Same format sniffing as
// read_image_from_memory.
std::array<uint64_t, 3> encoded_image_size(const std::vector<unsigned char>& bytes) {
  OIIO::Filesystem::IOMemReader reader(bytes.data(), bytes.size());
  const bool jpeg = bytes.size() >= 3 && bytes[0] == 0xFF && bytes[1] == 0xD8;
  const bool webp = bytes.size() >= 12 && std::memcmp(bytes.data(), "RIFF", 4) == 0 &&
                    std::memcmp(bytes.data() + 8, "WEBP", 4) == 0;
  // A PNG whose chunks run past its end never reaches OIIO (png_structure.h says why).
  if (!jpeg && !webp && !png_structure_error(bytes.data(), bytes.size()).empty()) return {0, 0, 0};
  auto in = OIIO::ImageInput::open(jpeg ? "in-memory.jpg" : webp ? "in-memory.webp" : "in-memory.png", nullptr,
                                   &reader);
  if (!in) {
    OIIO::geterror();  // clear the message: read_image_from_memory produces its own
    return {0, 0, 0};
  }
  const OIIO::ImageSpec& spec = in->spec();
  auto non_negative = [](int v) { return static_cast<uint64_t>(std::max(v, 0)); };
  return {non_negative(spec.width), non_negative(spec.height), non_negative(spec.nchannels)};
}

WrapMode wrap_mode(const GltfContext& ctx, int sampler, int gl_wrap) {
  switch (gl_wrap) {
    case TINYGLTF_TEXTURE_WRAP_REPEAT:
      return WrapMode::Repeat;
    case TINYGLTF_TEXTURE_WRAP_CLAMP_TO_EDGE:
      return WrapMode::ClampToEdge;
    case TINYGLTF_TEXTURE_WRAP_MIRRORED_REPEAT:
      return WrapMode::MirroredRepeat;
    default:
      ctx.warn("sampler {} has unknown wrap mode {}: REPEAT used", sampler, gl_wrap);
      return WrapMode::Repeat;
  }
}

// Expands 1-4 channels to RGBA: grey replicates, a missing alpha is opaque.
std::vector<glm::vec4> to_rgba(const Image& image) {
  std::vector<glm::vec4> texels(static_cast<size_t>(image.width) * image.height);
  const int c = image.channels;
  for (size_t i = 0; i < texels.size(); ++i) {
    const float* p = &image.pixels[i * static_cast<size_t>(c)];
    if (c >= 3)
      texels[i] = glm::vec4(p[0], p[1], p[2], c >= 4 ? p[3] : 1.0f);
    else
      texels[i] = glm::vec4(p[0], p[0], p[0], c == 2 ? p[1] : 1.0f);
  }
  return texels;
}

// The same for 8-bit codes (255 = opaque).
std::vector<uint8_t> to_rgba(const ByteImage& image) {
  const size_t texels = static_cast<size_t>(image.width) * image.height;
  std::vector<uint8_t> rgba(4 * texels);
  const int c = image.channels;
  for (size_t i = 0; i < texels; ++i) {
    const uint8_t* p = &image.codes[i * static_cast<size_t>(c)];
    uint8_t* q = &rgba[4 * i];
    if (c >= 3) {
      q[0] = p[0], q[1] = p[1], q[2] = p[2], q[3] = c >= 4 ? p[3] : 255;
    } else {
      q[0] = q[1] = q[2] = p[0];
      q[3] = c == 2 ? p[1] : 255;
    }
  }
  return rgba;
}

// Half holds finite values up to 65504; a texel beyond that keeps the texture in float.
bool fits_half(const std::vector<glm::vec4>& texels) {
  for (const glm::vec4& t : texels)
    for (int c = 0; c < 4; ++c)
      if (std::isfinite(t[c]) && std::abs(t[c]) > 65504.0f) return false;
  return true;
}

// Stores a decoded image's texels in `texture`: 8-bit images keep their codes (sRGB-decoded
// at lookup for colour), deeper ones are decoded now and kept as half.
void store_texels(Texture& texture, const std::variant<ByteImage, Image>& image) {
  const bool colour = texture.encoding == TextureEncoding::SrgbColour;
  if (const ByteImage* codes = std::get_if<ByteImage>(&image)) {
    texture.assign_codes(codes->width, codes->height, to_rgba(*codes),
                         colour ? TexelFormat::Srgb8 : TexelFormat::Unorm8);
    return;
  }
  Image pixels = std::get<Image>(image);  // a copy: the sRGB decode is per use
  if (colour) srgb_to_linear(pixels);
  const std::vector<glm::vec4> texels = to_rgba(pixels);
  const TexelFormat format = fits_half(texels) ? TexelFormat::Half : TexelFormat::Float;
  texture.assign_linear(pixels.width, pixels.height, texels, format);
}

// The image's name, else its file URI, else "image N" (data URIs are not names).
std::string display_name(const tinygltf::Image& image, int index) {
  if (!image.name.empty()) return image.name;
  if (!image.uri.empty() && image.uri.rfind("data:", 0) != 0) return image.uri;
  return fmt::format("image {}", index);
}

}  // namespace

TextureTable::TextureTable(const GltfContext& ctx, std::vector<Texture>& scene_textures, bool decode)
    : ctx_(ctx), textures_(scene_textures), decode_(decode) {}

int TextureTable::get(int texture, TextureEncoding encoding, const std::string& role) {
  if (!in_range(texture, ctx_.model.textures.size()))
    ctx_.fail("{} refers to texture {}, which does not exist ({} textures)", role, texture,
              ctx_.model.textures.size());
  const auto key = std::make_pair(texture, encoding);
  const auto found = entries_.find(key);
  if (found != entries_.end()) return found->second;
  const int image = image_index(texture, role);
  textures_.push_back(make_texture(texture, image, encoding));
  const int index = static_cast<int>(textures_.size()) - 1;
  image_of_.emplace_back(static_cast<size_t>(index), image);
  entries_.emplace(key, index);
  return index;
}

// EXT_texture_webp's image when the texture has one: it is the optimised copy tools write,
// and OIIO decodes it. Otherwise the core source; KHR_texture_basisu's KTX2 has no decoder
// here (none in Debian), so the core source stands in for it, with a warning.
int TextureTable::image_index(int texture_index, const std::string& role) {
  const tinygltf::Texture& source = ctx_.model.textures[static_cast<size_t>(texture_index)];
  const std::string texture_name = label("texture", texture_index, ctx_.model.textures);
  const auto webp = source.extensions.find(kWebp);
  if (webp != source.extensions.end()) {
    const std::string where = texture_name + " " + kWebp;
    const std::optional<int> image = integer_member(ctx_, webp->second, "source", where);
    if (!image) ctx_.fail("{} has no source", where);
    if (!in_range(*image, ctx_.model.images.size()))
      ctx_.fail("{} source {} does not exist ({} images)", where, *image, ctx_.model.images.size());
    return *image;
  }
  const bool basisu = source.extensions.count(kBasisu) != 0;
  if (!in_range(source.source, ctx_.model.images.size())) {
    if (basisu)
      ctx_.fail("{} (used by {}) has only a {} (KTX2) image, which this loader cannot decode (no Basis "
                "Universal transcoder), and no core source to fall back on",
                texture_name, role, kBasisu);
    ctx_.fail("{} (used by {}) has no valid image source (source {}, {} images)", texture_name, role,
              source.source, ctx_.model.images.size());
  }
  if (basisu && warned_basisu_.insert(texture_index).second)
    ctx_.warn("{}: its {} (KTX2) image is not decoded (no Basis Universal transcoder): core source image {} used",
              texture_name, kBasisu, source.source);
  return source.source;
}

Texture TextureTable::make_texture(int texture_index, int image_source, TextureEncoding encoding) {
  const tinygltf::Texture& source = ctx_.model.textures[static_cast<size_t>(texture_index)];
  const std::string texture_name = label("texture", texture_index, ctx_.model.textures);
  const tinygltf::Image& image = ctx_.model.images[static_cast<size_t>(image_source)];

  Texture texture;
  texture.name = display_name(image, image_source);
  texture.encoding = encoding;
  if (source.sampler >= 0) {
    if (!in_range(source.sampler, ctx_.model.samplers.size()))
      ctx_.fail("{} refers to sampler {}, which does not exist ({} samplers)", texture_name, source.sampler,
                ctx_.model.samplers.size());
    const tinygltf::Sampler& sampler = ctx_.model.samplers[static_cast<size_t>(source.sampler)];
    texture.wrap_s = wrap_mode(ctx_, source.sampler, sampler.wrapS);
    texture.wrap_t = wrap_mode(ctx_, source.sampler, sampler.wrapT);
    texture.nearest = sampler.magFilter == TINYGLTF_TEXTURE_FILTER_NEAREST;
  }
  return texture;
}

void TextureTable::decode_all() {
  if (!decode_) return;
  // Each image once, with the textures that show it; images in order of their first texture.
  std::vector<int> images;
  std::vector<std::vector<size_t>> users;
  std::map<int, size_t> slot_of_image;
  for (const auto& [texture, image] : image_of_) {
    const auto [slot, first] = slot_of_image.emplace(image, images.size());
    if (first) {
      images.push_back(image);
      users.emplace_back();
    }
    users[slot->second].push_back(texture);
  }
  // Errors are kept per image and the first rethrown: TBB would pass on whichever came first
  // in time.
  std::vector<std::exception_ptr> errors(images.size());
  tbb::parallel_for(size_t(0), images.size(), [&](size_t i) {
    try {
      decode_image(images[i], users[i]);
    } catch (...) {
      errors[i] = std::current_exception();
    }
  });
  for (const std::exception_ptr& error : errors)
    if (error) std::rethrow_exception(error);
}

void TextureTable::decode_image(int index, const std::vector<size_t>& textures) {
  const tinygltf::Image& image = ctx_.model.images[static_cast<size_t>(index)];
  const std::string what = fmt::format("{}: {}", ctx_.file(), label("image", index, ctx_.model.images));
  if (image.image.empty()) phyir::fail("{} has no data (uri '{}')", what, image.uri.substr(0, 200));
  const auto [width, height, channels] = encoded_image_size(image.image);
  if (width * height * channels > kMaxTextureValues)  // each <= 2^31: no overflow
    phyir::fail("{} is {} x {} pixels x {} channels, more than a texture may hold (2^28 values, 1 GiB as float)",
                what, width, height, channels);
  const std::variant<ByteImage, Image> decoded = read_image_from_memory_at_file_depth(image.image, what);
  for (size_t texture : textures) store_texels(textures_[texture], decoded);
}

}  // namespace phyir::scenes::gltf
