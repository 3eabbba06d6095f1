#pragma once
// A decoded texture: linear float RGBA texels plus the glTF sampler state. Colour
// textures (base colour, emissive) are sRGB-decoded at load time through OpenColorIO;
// data textures (metallic-roughness, normal, transmission) stay as stored.
#include <glm/glm.hpp>

#include <string>
#include <vector>

namespace phyir::scenes {

enum class WrapMode { Repeat, ClampToEdge, MirroredRepeat };
enum class TextureEncoding { SrgbColour, LinearData };

// One level of a texture's mip pyramid.
struct TextureLevel {
  int width = 0;
  int height = 0;
  std::vector<glm::vec4> texels;  // row-major, row 0 = top
};

struct Texture {
  std::string name;    // image name or URI, for messages
  int width = 0;
  int height = 0;
  std::vector<glm::vec4> texels;  // row-major, row 0 = top of the image (v = 0)
  WrapMode wrap_s = WrapMode::Repeat;
  WrapMode wrap_t = WrapMode::Repeat;
  bool nearest = false;  // magFilter NEAREST
  TextureEncoding encoding = TextureEncoding::LinearData;
  // Levels 1, 2, ... of the mip pyramid (level 0 is `texels`), each half the size of the
  // one before, down to 1x1; empty until build_mips().
  std::vector<TextureLevel> mips;

  // Bilinear (or nearest) lookup at glTF UV (u right, v down, (0,0) = top-left corner of
  // the image), honouring the wrap modes.
  glm::vec4 sample(glm::vec2 uv) const;
  // Trilinear lookup at mip level `lod` (0 = full resolution; between two levels, the blend
  // of both; clamped to the pyramid). Without mips, or at lod <= 0, sample(uv).
  glm::vec4 sample(glm::vec2 uv, float lod) const;
  int levels() const { return 1 + static_cast<int>(mips.size()); }
};

// Builds `texture.mips` by repeated halving with OpenImageIO's box filter (each texel of a
// level is the mean of the 2x2 texels below it; odd sizes round up). A third more memory.
void build_mips(Texture& texture);

}  // namespace phyir::scenes
