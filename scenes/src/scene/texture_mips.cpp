// The mip pyramid of a texture, halved level by level with OpenImageIO's box filter. The
// halving runs on linear floats carried from level to level; only the stored copy of each
// level is re-encoded, so quantisation never compounds up the pyramid and the level means
// stay those of the float pyramid.
#include <OpenImageIO/imagebuf.h>
#include <OpenImageIO/imagebufalgo.h>

#include <algorithm>

#include "phyir/core/error.h"
#include "phyir/scenes/texture.h"
#include "scene/texel_codec.h"

namespace phyir::scenes {

namespace {

// Linear texels of one level, kept in float while the pyramid is built.
struct LinearLevel {
  int width = 0;
  int height = 0;
  std::vector<glm::vec4> texels;
};

LinearLevel half_of(const LinearLevel& from_level, const std::string& name) {
  const OIIO::ImageSpec from_spec(from_level.width, from_level.height, 4, OIIO::TypeDesc::FLOAT);
  const OIIO::ImageBuf from(from_spec, const_cast<glm::vec4*>(from_level.texels.data()));
  LinearLevel half;
  half.width = std::max(1, (from_level.width + 1) / 2);
  half.height = std::max(1, (from_level.height + 1) / 2);
  OIIO::ImageBuf to(OIIO::ImageSpec(half.width, half.height, 4, OIIO::TypeDesc::FLOAT));
  if (!OIIO::ImageBufAlgo::resize(to, from, "box", 0.0f, OIIO::ROI(), 1))
    fail("texture '{}': mip level {}x{} could not be built: {}", name, half.width, half.height, to.geterror());
  half.texels.resize(size_t(half.width) * size_t(half.height));
  to.get_pixels(OIIO::ROI::All(), OIIO::TypeDesc::FLOAT, half.texels.data());
  return half;
}

}  // namespace

void Texture::build_mips() {
  if (levels_.empty()) return;
  levels_.resize(1);
  const TextureLevel& top = levels_[0];
  LinearLevel level{top.width, top.height, texels::decode_level(format_, top)};
  while (level.width > 1 || level.height > 1) {
    level = half_of(level, name);
    levels_.push_back(texels::encode_level(format_, level.width, level.height, level.texels));
  }
}

}  // namespace phyir::scenes
