#pragma once
// A texture: its texels in a compact storage format, their mip pyramid and the glTF sampler
// state. Lookups return linear float RGBA whatever the storage. Colour textures (base colour,
// emissive) are sRGB-decoded through OpenColorIO; data textures (metallic-roughness, normal,
// transmission) stay as stored.
#include <glm/glm.hpp>

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

namespace phyir::scenes {

enum class WrapMode { Repeat, ClampToEdge, MirroredRepeat };
enum class TextureEncoding { SrgbColour, LinearData };

// How texels are stored (always four channels, RGBA).
enum class TexelFormat {
  Srgb8,   // 8-bit sRGB code values: RGB decoded at lookup through a 256-entry table of the
           // OpenColorIO decode, alpha as code / 255. 4 bytes a texel.
  Unorm8,  // 8-bit linear code values, code / 255. 4 bytes a texel.
  Half,    // 16-bit floats, linear (Imath::half). 8 bytes a texel.
  Float,   // 32-bit floats, linear. 16 bytes a texel.
};

// One level of the mip pyramid. Exactly one of the vectors holds the texels (row-major,
// row 0 = top), the one of the texture's format: codes 4 per texel, halves 4 per texel (Imath
// half bits), floats one per texel.
struct TextureLevel {
  int width = 0;
  int height = 0;
  std::vector<uint8_t> codes;
  std::vector<uint16_t> halves;
  std::vector<glm::vec4> floats;
};

class Texture {
 public:
  std::string name;  // image name or URI, for messages
  WrapMode wrap_s = WrapMode::Repeat;
  WrapMode wrap_t = WrapMode::Repeat;
  bool nearest = false;  // magFilter NEAREST
  TextureEncoding encoding = TextureEncoding::LinearData;

  // No texels (a texture not decoded): lookups return white.
  Texture() = default;

  // From linear float RGBA texels (row-major, row 0 = top of the image, v = 0), stored as
  // `format`: Float keeps them exactly (what tests and generated textures want), Half rounds
  // them to 16-bit floats, Srgb8 and Unorm8 to the code value whose decode is nearest.
  static Texture from_linear(int width, int height, const std::vector<glm::vec4>& texels,
                             TexelFormat format = TexelFormat::Float);
  // From 8-bit RGBA code values as an image file stores them (row-major, row 0 = top);
  // `format` is Srgb8 or Unorm8 and says how they decode.
  static Texture from_codes(int width, int height, std::vector<uint8_t> rgba, TexelFormat format);
  // The same on an existing texture (its name and sampler state kept, any mips dropped).
  void assign_linear(int width, int height, const std::vector<glm::vec4>& texels,
                     TexelFormat format = TexelFormat::Float);
  void assign_codes(int width, int height, std::vector<uint8_t> rgba, TexelFormat format);

  int width() const { return levels_.empty() ? 0 : levels_[0].width; }
  int height() const { return levels_.empty() ? 0 : levels_[0].height; }
  TexelFormat format() const { return format_; }
  bool has_texels() const { return !levels_.empty(); }
  // Texels of the full-resolution level (0 without texels).
  size_t texel_count() const { return size_t(width()) * size_t(height()); }
  // Mip levels: 1 (full resolution only) until build_mips(); 1 without texels too.
  int levels() const { return levels_.empty() ? 1 : static_cast<int>(levels_.size()); }
  int level_width(int level) const { return levels_.at(static_cast<size_t>(level)).width; }
  int level_height(int level) const { return levels_.at(static_cast<size_t>(level)).height; }
  // Texel (x, y) of mip level `level`, linear RGBA; x, y, level must be in range.
  glm::vec4 texel(int x, int y, int level = 0) const;
  // Memory the texels take, every mip level included.
  size_t bytes() const;

  // Bilinear (or nearest) lookup at glTF UV (u right, v down, (0,0) = top-left corner of
  // the image), honouring the wrap modes.
  glm::vec4 sample(glm::vec2 uv) const;
  // Trilinear lookup at mip level `lod` (0 = full resolution; between two levels, the blend
  // of both; clamped to the pyramid). Without mips, or at lod <= 0, sample(uv).
  glm::vec4 sample(glm::vec2 uv, float lod) const;

  // Builds the mip pyramid by repeated halving with OpenImageIO's box filter on the linear
  // values (each texel of a level is the mean of the 2x2 texels below it; odd sizes round up),
  // each level then stored in the texture's format. A third more memory.
  void build_mips();

 private:
  TexelFormat format_ = TexelFormat::Float;
  std::vector<TextureLevel> levels_;  // [0] = full resolution, then halved down to 1x1
};

}  // namespace phyir::scenes
