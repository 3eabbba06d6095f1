// The mip pyramid of a texture, halved level by level with OpenImageIO's box filter.
#include <OpenImageIO/imagebuf.h>
#include <OpenImageIO/imagebufalgo.h>

#include <algorithm>

#include "phyir/core/error.h"
#include "phyir/scenes/texture.h"

namespace phyir::scenes {

namespace {


TextureLevel half_of(const std::vector<glm::vec4>& texels, int width, int height, const std::string& name) {
  const OIIO::ImageSpec from_spec(width, height, 4, OIIO::TypeDesc::FLOAT);
  const OIIO::ImageBuf from(from_spec, const_cast<glm::vec4*>(texels.data()));
  TextureLevel half;
  half.width = std::max(1, (width + 1) / 2);
  half.height = std::max(1, (height + 1) / 2);
  OIIO::ImageBuf to(OIIO::ImageSpec(half.width, half.height, 4, OIIO::TypeDesc::FLOAT));
  if (!OIIO::ImageBufAlgo::resize(to, from, "box", 0.0f, OIIO::ROI(), 1))
    fail("texture '{}': mip level {}x{} could not be built: {}", name, half.width, half.height, to.geterror());
  half.texels.resize(size_t(half.width) * size_t(half.height));
  to.get_pixels(OIIO::ROI::All(), OIIO::TypeDesc::FLOAT, half.texels.data());
  return half;
}

}  // namespace

void build_mips(Texture& texture) {
  texture.mips.clear();
  int width = texture.width, height = texture.height;
  const std::vector<glm::vec4>* texels = &texture.texels;
  if (texels->size() != size_t(width) * size_t(height) || texels->empty()) return;
  while (width > 1 || height > 1) {
    texture.mips.push_back(half_of(*texels, width, height, texture.name));
    width = texture.mips.back().width;
    height = texture.mips.back().height;
    texels = &texture.mips.back().texels;
  }
}

}  // namespace phyir::scenes
