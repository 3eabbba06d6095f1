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

struct Texture {
  std::string name;    // image name or URI, for messages
  int width = 0;
  int height = 0;
  std::vector<glm::vec4> texels;  // row-major, row 0 = top of the image (v = 0)
  WrapMode wrap_s = WrapMode::Repeat;
  WrapMode wrap_t = WrapMode::Repeat;
  bool nearest = false;  // magFilter NEAREST
  TextureEncoding encoding = TextureEncoding::LinearData;

  // Bilinear (or nearest) lookup at glTF UV (u right, v down, (0,0) = top-left corner of
  // the image), honouring the wrap modes.
  glm::vec4 sample(glm::vec2 uv) const;
};

}  // namespace phyir::scenes
