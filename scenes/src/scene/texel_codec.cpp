// Imath's half conversions without its lookup table, before anything includes half.h: the
// table lives in libImath, which phyir_scenes does not link.
#define IMATH_HALF_NO_LOOKUP_TABLE
#include <Imath/half.h>

#include "scene/texel_codec.h"

#include <algorithm>

#include "phyir/core/colour.h"
#include "phyir/core/image.h"

namespace phyir::scenes::texels {

namespace {

// For encoding: the code whose decode is nearest to a linear value, for one rising table. A
// binary search per value stood out in the big room's load profile (four per mip texel), so
// a bucket index over [0, 1] gives the first candidate and a step or two finds the code.
class NearestCode {
 public:
  explicit NearestCode(const std::array<float, 256>& table) : table_(table) {
    for (int b = 0; b <= kBuckets; ++b) {
      const float start = float(b) / kBuckets;
      first_[size_t(b)] = uint8_t(std::lower_bound(table.begin(), table.end() - 1, start) - table.begin());
    }
  }

  // NaN and values below the table give 0, values above it 255.
  uint8_t operator()(float v) const {
    if (!(v > table_.front())) return 0;
    if (v >= table_.back()) return 255;
    // First code whose decode is >= v: at or after the bucket's first (v >= the bucket start).
    size_t above = first_[std::min(size_t(v * kBuckets), size_t(kBuckets))];
    while (table_[above] < v) ++above;
    const size_t below = above - 1;  // exists: v > table_.front()
    return uint8_t(v - table_[below] <= table_[above] - v ? below : above);
  }

 private:
  // 4096 buckets: narrower than the smallest step between sRGB codes (1 / (255 x 12.92)), so
  // the walk is at most a step or two.
  static constexpr int kBuckets = 4096;
  const std::array<float, 256>& table_;
  std::array<uint8_t, kBuckets + 1> first_;
};

const NearestCode& srgb8_encoder() {
  static const NearestCode encoder(srgb8_decode_table());
  return encoder;
}

const NearestCode& unorm8_encoder() {
  static const NearestCode encoder(unorm8_decode_table());
  return encoder;
}

std::vector<uint8_t> encode_codes(const std::vector<glm::vec4>& linear, const NearestCode& rgb,
                                  const NearestCode& alpha) {
  std::vector<uint8_t> codes(4 * linear.size());
  for (size_t i = 0; i < linear.size(); ++i) {
    for (int c = 0; c < 3; ++c) codes[4 * i + size_t(c)] = rgb(linear[i][c]);
    codes[4 * i + 3] = alpha(linear[i].w);
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

// OpenImageIO's 8-bit to float conversion (fmath.h, convert_type<uint8_t, float>): the code
// times the float 1/255, which is not always the code divided by 255 in float.
std::array<float, 256> make_unorm8_decode_table() {
  const float scale = 1.0f / 255.0f;
  std::array<float, 256> scaled;
  for (int code = 0; code < 256; ++code) scaled[static_cast<size_t>(code)] = static_cast<float>(code) * scale;
  return scaled;
}

std::array<float, 256> make_srgb8_decode_table() {
  const std::array<float, 256>& scaled = unorm8_decode_table();
  Image codes(256, 1, 3);  // every code in every channel, decoded the way a texture image is
  for (int i = 0; i < 256; ++i)
    for (int c = 0; c < 3; ++c) codes.at(i, 0, c) = scaled[static_cast<size_t>(i)];
  srgb_to_linear(codes);
  std::array<float, 256> table;
  for (int i = 0; i < 256; ++i) table[static_cast<size_t>(i)] = codes.at(i, 0, 0);
  return table;
}

TextureLevel encode_level(TexelFormat format, int width, int height, const std::vector<glm::vec4>& linear) {
  TextureLevel level;
  level.width = width;
  level.height = height;
  switch (format) {
    case TexelFormat::Srgb8: level.codes = encode_codes(linear, srgb8_encoder(), unorm8_encoder()); break;
    case TexelFormat::Unorm8: level.codes = encode_codes(linear, unorm8_encoder(), unorm8_encoder()); break;
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
