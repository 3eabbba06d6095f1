#include "gltf_textures.h"

#include <OpenImageIO/filesystem.h>
#include <OpenImageIO/imageio.h>

#include <algorithm>
#include <array>
#include <cstring>

#include "gltf_values.h"
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
  textures_.push_back(make_texture(texture, encoding, role));
  const int index = static_cast<int>(textures_.size()) - 1;
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

Texture TextureTable::make_texture(int texture_index, TextureEncoding encoding, const std::string& role) {
  const tinygltf::Texture& source = ctx_.model.textures[static_cast<size_t>(texture_index)];
  const std::string texture_name = label("texture", texture_index, ctx_.model.textures);
  const int image_source = image_index(texture_index, role);
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
  if (!decode_) return texture;

  Image pixels = decoded_image(image_source);  // a copy: the sRGB decode is per use
  if (encoding == TextureEncoding::SrgbColour) srgb_to_linear(pixels);
  texture.width = pixels.width;
  texture.height = pixels.height;
  texture.texels = to_rgba(pixels);
  return texture;
}

const Image& TextureTable::decoded_image(int index) {
  const auto found = images_.find(index);
  if (found != images_.end()) return found->second;
  const tinygltf::Image& image = ctx_.model.images[static_cast<size_t>(index)];
  const std::string what = fmt::format("{}: {}", ctx_.file(), label("image", index, ctx_.model.images));
  if (image.image.empty()) phyir::fail("{} has no data (uri '{}')", what, image.uri.substr(0, 200));
  const auto [width, height, channels] = encoded_image_size(image.image);
  if (width * height * channels > kMaxTextureValues)  // each <= 2^31: no overflow
    phyir::fail("{} is {} x {} pixels x {} channels, more than a texture may hold (2^28 values, 1 GiB as float)",
                what, width, height, channels);
  return images_.emplace(index, read_image_from_memory(image.image, what)).first->second;
}

}  // namespace phyir::scenes::gltf
