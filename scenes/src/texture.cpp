#include "phyir/scenes/texture.h"

#include <algorithm>
#include <cmath>

namespace phyir::scenes {

namespace {

int wrap_index(int i, int n, WrapMode mode) {
  switch (mode) {
    case WrapMode::ClampToEdge: return i < 0 ? 0 : (i >= n ? n - 1 : i);
    case WrapMode::MirroredRepeat: {
      const int period = 2 * n;
      int m = i % period;
      if (m < 0) m += period;
      return m < n ? m : period - 1 - m;
    }
    case WrapMode::Repeat:
    default: {
      int m = i % n;
      return m < 0 ? m + n : m;
    }
  }
}

// Bilinear (or nearest) lookup in one level.
glm::vec4 lookup(const std::vector<glm::vec4>& texels, int width, int height, glm::vec2 uv, const Texture& t,
                 bool nearest) {
  // Texel centres sit at (i + 0.5) / width.
  const float x = uv.x * width - 0.5f;
  const float y = uv.y * height - 0.5f;
  if (nearest) {
    const int ix = wrap_index(static_cast<int>(std::floor(x + 0.5f)), width, t.wrap_s);
    const int iy = wrap_index(static_cast<int>(std::floor(y + 0.5f)), height, t.wrap_t);
    return texels[static_cast<size_t>(iy) * width + ix];
  }
  const float fx = std::floor(x), fy = std::floor(y);
  const float tx = x - fx, ty = y - fy;
  const int x0 = wrap_index(static_cast<int>(fx), width, t.wrap_s);
  const int x1 = wrap_index(static_cast<int>(fx) + 1, width, t.wrap_s);
  const int y0 = wrap_index(static_cast<int>(fy), height, t.wrap_t);
  const int y1 = wrap_index(static_cast<int>(fy) + 1, height, t.wrap_t);
  auto at = [&](int xi, int yi) { return texels[static_cast<size_t>(yi) * width + xi]; };
  return glm::mix(glm::mix(at(x0, y0), at(x1, y0), tx), glm::mix(at(x0, y1), at(x1, y1), tx), ty);
}

glm::vec2 finite_uv(glm::vec2 uv) { return std::isfinite(uv.x) && std::isfinite(uv.y) ? uv : glm::vec2(0.0f); }

}  // namespace

glm::vec4 Texture::sample(glm::vec2 uv) const {
  if (texels.empty()) return glm::vec4(1.0f);
  return lookup(texels, width, height, finite_uv(uv), *this, nearest);
}

glm::vec4 Texture::sample(glm::vec2 uv, float lod) const {
  if (mips.empty() || !(lod > 0.0f)) return sample(uv);
  uv = finite_uv(uv);
  const float top = static_cast<float>(mips.size());
  lod = std::min(lod, top);
  const int below = static_cast<int>(std::floor(lod));
  const float blend = lod - static_cast<float>(below);
  // Minified: magFilter NEAREST no longer applies.
  auto level = [&](int k) {
    if (k == 0) return lookup(texels, width, height, uv, *this, false);
    const TextureLevel& m = mips[static_cast<size_t>(k - 1)];
    return lookup(m.texels, m.width, m.height, uv, *this, false);
  };
  const glm::vec4 a = level(below);
  return blend > 0.0f && below < static_cast<int>(mips.size()) ? glm::mix(a, level(below + 1), blend) : a;
}

}  // namespace phyir::scenes
