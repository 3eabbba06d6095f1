#include "phyir/scenes/texture.h"

#include <algorithm>
#include <cmath>

#include "phyir/core/error.h"
#include "scene/texel_codec.h"

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

// Bilinear (or nearest) lookup in one level; `read(i)` is texel i, linear.
template <typename Reader>
glm::vec4 lookup(const Reader& read, int width, int height, glm::vec2 uv, const Texture& t, bool nearest) {
  // Texel centres sit at (i + 0.5) / width.
  const float x = uv.x * width - 0.5f;
  const float y = uv.y * height - 0.5f;
  if (nearest) {
    const int ix = wrap_index(static_cast<int>(std::floor(x + 0.5f)), width, t.wrap_s);
    const int iy = wrap_index(static_cast<int>(std::floor(y + 0.5f)), height, t.wrap_t);
    return read(static_cast<size_t>(iy) * width + ix);
  }
  const float fx = std::floor(x), fy = std::floor(y);
  const float tx = x - fx, ty = y - fy;
  const int x0 = wrap_index(static_cast<int>(fx), width, t.wrap_s);
  const int x1 = wrap_index(static_cast<int>(fx) + 1, width, t.wrap_s);
  const int y0 = wrap_index(static_cast<int>(fy), height, t.wrap_t);
  const int y1 = wrap_index(static_cast<int>(fy) + 1, height, t.wrap_t);
  auto at = [&](int xi, int yi) { return read(static_cast<size_t>(yi) * width + xi); };
  return glm::mix(glm::mix(at(x0, y0), at(x1, y0), tx), glm::mix(at(x0, y1), at(x1, y1), tx), ty);
}

glm::vec4 lookup_level(TexelFormat format, const TextureLevel& level, glm::vec2 uv, const Texture& t, bool nearest) {
  return texels::with_reader(format, level, [&](const auto& read) {
    return lookup(read, level.width, level.height, uv, t, nearest);
  });
}

glm::vec2 finite_uv(glm::vec2 uv) { return std::isfinite(uv.x) && std::isfinite(uv.y) ? uv : glm::vec2(0.0f); }

void check_size(int width, int height, size_t values, size_t per_texel, const char* what) {
  if (width <= 0 || height <= 0 || values != size_t(width) * size_t(height) * per_texel)
    fail("Texture::{}: {} values do not make a {} x {} texture ({} per texel)", what, values, width, height,
         per_texel);
}

}  // namespace

Texture Texture::from_linear(int width, int height, const std::vector<glm::vec4>& texels, TexelFormat format) {
  Texture texture;
  texture.assign_linear(width, height, texels, format);
  return texture;
}

Texture Texture::from_codes(int width, int height, std::vector<uint8_t> rgba, TexelFormat format) {
  Texture texture;
  texture.assign_codes(width, height, std::move(rgba), format);
  return texture;
}

void Texture::assign_linear(int width, int height, const std::vector<glm::vec4>& texels, TexelFormat format) {
  check_size(width, height, texels.size(), 1, "assign_linear");
  format_ = format;
  levels_.assign(1, texels::encode_level(format, width, height, texels));
}

void Texture::assign_codes(int width, int height, std::vector<uint8_t> rgba, TexelFormat format) {
  check_size(width, height, rgba.size(), 4, "assign_codes");
  if (format != TexelFormat::Srgb8 && format != TexelFormat::Unorm8)
    fail("Texture::assign_codes: 8-bit codes need the Srgb8 or Unorm8 format");
  format_ = format;
  levels_.assign(1, TextureLevel{width, height, std::move(rgba), {}, {}});
}

glm::vec4 Texture::texel(int x, int y, int level) const {
  const TextureLevel& l = levels_.at(static_cast<size_t>(level));
  return texels::with_reader(format_, l, [&](const auto& read) { return read(static_cast<size_t>(y) * l.width + x); });
}

size_t Texture::bytes() const {
  size_t total = 0;
  for (const TextureLevel& level : levels_) total += texels::level_bytes(level);
  return total;
}

glm::vec4 Texture::sample(glm::vec2 uv) const {
  if (levels_.empty()) return glm::vec4(1.0f);
  return lookup_level(format_, levels_[0], finite_uv(uv), *this, nearest);
}

glm::vec4 Texture::sample(glm::vec2 uv, float lod) const {
  if (levels_.size() < 2 || !(lod > 0.0f)) return sample(uv);
  uv = finite_uv(uv);
  const float top = static_cast<float>(levels_.size() - 1);
  lod = std::min(lod, top);
  const int below = static_cast<int>(std::floor(lod));
  const float blend = lod - static_cast<float>(below);
  // Minified: magFilter NEAREST no longer applies.
  auto level = [&](int k) { return lookup_level(format_, levels_[static_cast<size_t>(k)], uv, *this, false); };
  const glm::vec4 a = level(below);
  return blend > 0.0f && below < static_cast<int>(levels_.size() - 1) ? glm::mix(a, level(below + 1), blend) : a;
}

}  // namespace phyir::scenes
