#pragma once
// Texel storage formats: how a stored texel becomes linear RGBA (decode, at every lookup) and
// how linear RGBA becomes a stored texel (encode, when a texture or a mip level is made).
#include <array>
#include <cstddef>
#include <cstdint>
#include <vector>

#include "phyir/scenes/texture.h"

namespace phyir::scenes::texels {

// Linear value of each 8-bit sRGB code: OpenColorIO's srgb_texture -> scene_linear transform
// (the one srgb_to_linear applies) of the code scaled as OpenImageIO scales 8-bit data, so a
// table lookup equals decoding the image as float and then through OCIO.
std::array<float, 256> make_srgb8_decode_table();
// Each 8-bit code scaled to [0, 1] exactly as OpenImageIO converts 8-bit data to float.
std::array<float, 256> make_unorm8_decode_table();

// The tables, built on first use. Inline: every lookup asks for them.
inline const std::array<float, 256>& srgb8_decode_table() {
  static const std::array<float, 256> table = make_srgb8_decode_table();
  return table;
}
inline const std::array<float, 256>& unorm8_decode_table() {
  static const std::array<float, 256> table = make_unorm8_decode_table();
  return table;
}

// Readers of one level's texels by index, one per format: reader(i) is texel i, linear RGBA.
struct Srgb8Reader {
  const uint8_t* codes;
  const float* rgb;    // srgb8_decode_table
  const float* alpha;  // unorm8_decode_table: alpha is never sRGB-encoded
  glm::vec4 operator()(size_t i) const {
    const uint8_t* c = codes + 4 * i;
    return {rgb[c[0]], rgb[c[1]], rgb[c[2]], alpha[c[3]]};
  }
};

struct Unorm8Reader {
  const uint8_t* codes;
  const float* table;  // unorm8_decode_table
  glm::vec4 operator()(size_t i) const {
    const uint8_t* c = codes + 4 * i;
    return {table[c[0]], table[c[1]], table[c[2]], table[c[3]]};
  }
};

// Imath's conversion of 16-bit float bits (exact; the arithmetic one, not its 256 KiB table,
// which would need libImath linked).
float half_to_float(uint16_t bits);
uint16_t float_to_half(float value);

struct HalfReader {
  const uint16_t* bits;
  glm::vec4 operator()(size_t i) const {
    const uint16_t* h = bits + 4 * i;
    return {half_to_float(h[0]), half_to_float(h[1]), half_to_float(h[2]), half_to_float(h[3])};
  }
};

struct FloatReader {
  const glm::vec4* texels;
  glm::vec4 operator()(size_t i) const { return texels[i]; }
};

// Calls f(reader) with the reader of `level`'s texels stored as `format`: one switch per call,
// so a lookup's four texel reads are direct.
template <typename F>
decltype(auto) with_reader(TexelFormat format, const TextureLevel& level, F&& f) {
  switch (format) {
    case TexelFormat::Srgb8:
      return f(Srgb8Reader{level.codes.data(), srgb8_decode_table().data(), unorm8_decode_table().data()});
    case TexelFormat::Unorm8:
      return f(Unorm8Reader{level.codes.data(), unorm8_decode_table().data()});
    case TexelFormat::Half:
      return f(HalfReader{level.halves.data()});
    case TexelFormat::Float:
    default:
      return f(FloatReader{level.floats.data()});
  }
}

// A level of `width` x `height` holding `linear` (row-major) stored as `format`: 8-bit formats
// take the code whose decode is nearest, Half rounds to nearest.
TextureLevel encode_level(TexelFormat format, int width, int height, const std::vector<glm::vec4>& linear);
// Every texel of `level`, linear RGBA, row-major.
std::vector<glm::vec4> decode_level(TexelFormat format, const TextureLevel& level);
// Memory of a level's texels.
size_t level_bytes(const TextureLevel& level);

}  // namespace phyir::scenes::texels
