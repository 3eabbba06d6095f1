// Imath's half conversions without its lookup table, before anything includes half.h: the
// table lives in libImath, which phyir_scenes does not link.
#define IMATH_HALF_NO_LOOKUP_TABLE
#include <Imath/half.h>

#include "texel_codec.h"

#include <algorithm>

#include "phyir/core/colour.h"
#include "phyir/core/image.h"

namespace phyir::scenes::texels {

namespace {

// OpenImageIO's 8-bit to float conversion (fmath.h, convert_type<uint8_t, float>): the code
// times the float 1/255, which is not always the code divided by 255 in float.
std::array<float, 256> scaled_codes() {
  const float scale = 1.0f / 255.0f;
  std::array<float, 256> scaled;
  for (int code = 0; code < 256; ++code) scaled[static_cast<size_t>(code)] = static_cast<float>(code) * scale;
  return scaled;
}

std::array<float, 256> srgb_decoded_codes() {
  const std::array<float, 256>& scaled = unorm8_decode_table();
  Image codes(256, 1, 3);  // every code in every channel, decoded the way a texture image is
  for (int i = 0; i < 256; ++i)
    for (int c = 0; c < 3; ++c) codes.at(i, 0, c) = scaled[static_cast<size_t>(i)];
  srgb_to_linear(codes);
  std::array<float, 256> table;
  for (int i = 0; i < 256; ++i) table[static_cast<size_t>(i)] = codes.at(i, 0, 0);
  return table;
}

// The code whose decode is nearest to v (the table rises with the code); NaN gives 0.
uint8_t nearest_code(float v, const std::array<float, 256>& table) {
  if (!(v > table.front())) return 0;
  const auto above = std::lower_bound(table.begin(), table.end(), v);
  if (above == table.end()) return 255;
  const auto below = above - 1;  // exists: v > table.front()
  return static_cast<uint8_t>((v - *below <= *above - v ? below : above) - table.begin());
}

std::vector<uint8_t> encode_codes(const std::vector<glm::vec4>& linear, const std::array<float, 256>& rgb,
                                  const std::array<float, 256>& alpha) {
  std::vector<uint8_t> codes(4 * linear.size());
  for (size_t i = 0; i < linear.size(); ++i) {
    for (int c = 0; c < 3; ++c) codes[4 * i + size_t(c)] = nearest_code(linear[i][c], rgb);
    codes[4 * i + 3] = nearest_code(linear[i].w, alpha);
  }
  return codes;
}

std::vector<uint16_t> encode_halves(const std::vector<glm::vec4>& linear) {
  std::vector<uint16_t> halves(4 * linear.size());
  for (size_t i = 0; i < linear.size(); ++i)
    for (int c = 0; c < 4; ++c) halves[4 * i + size_t(c)] = float_to_half(linear[i][c]);
  return halves;
}

}  // namespace

float half_to_float(uint16_t bits) { return imath_half_to_float(bits); }
uint16_t float_to_half(float value) { return imath_float_to_half(value); }

const std::array<float, 256>& unorm8_decode_table() {
  static const std::array<float, 256> table = scaled_codes();
  return table;
}

const std::array<float, 256>& srgb8_decode_table() {
  static const std::array<float, 256> table = srgb_decoded_codes();
  return table;
}

TextureLevel encode_level(TexelFormat format, int width, int height, const std::vector<glm::vec4>& linear) {
  TextureLevel level;
  level.width = width;
  level.height = height;
  switch (format) {
    case TexelFormat::Srgb8: level.codes = encode_codes(linear, srgb8_decode_table(), unorm8_decode_table()); break;
    case TexelFormat::Unorm8: level.codes = encode_codes(linear, unorm8_decode_table(), unorm8_decode_table()); break;
    case TexelFormat::Half: level.halves = encode_halves(linear); break;
    case TexelFormat::Float: level.floats = linear; break;
  }
  return level;
}

std::vector<glm::vec4> decode_level(TexelFormat format, const TextureLevel& level) {
  std::vector<glm::vec4> linear(size_t(level.width) * size_t(level.height));
  with_reader(format, level, [&](const auto& read) {
    for (size_t i = 0; i < linear.size(); ++i) linear[i] = read(i);
  });
  return linear;
}

size_t level_bytes(const TextureLevel& level) {
  return level.codes.size() + level.halves.size() * sizeof(uint16_t) + level.floats.size() * sizeof(glm::vec4);
}

}  // namespace phyir::scenes::texels
