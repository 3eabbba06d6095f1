#pragma once
// Where in its pixel a camera sample lands: the first two dimensions of the Sobol
// sequence (a (0,2)-sequence: every power-of-two prefix puts one point in each of its
// elementary rectangles), randomised per pixel by hash-based Owen scrambling (Burley 2020,
// "Practical Hash-based Owen Scrambling", JCGT 9(4)), which keeps that stratification and
// makes each point uniform. Independent jitter per sample leaves clumps and holes: at a
// light's edge, which covers part of a pixel with a radiance 100x its surroundings, that
// is most of an image's error (docs/cycles-comparison.md). Depends only on (pixel key,
// sample index), so images do not depend on the thread count.
#include <glm/glm.hpp>

#include <cstdint>

namespace phyir::render {

inline uint32_t reverse_bits(uint32_t x) {
  x = ((x >> 1) & 0x55555555u) | ((x & 0x55555555u) << 1);
  x = ((x >> 2) & 0x33333333u) | ((x & 0x33333333u) << 2);
  x = ((x >> 4) & 0x0F0F0F0Fu) | ((x & 0x0F0F0F0Fu) << 4);
  x = ((x >> 8) & 0x00FF00FFu) | ((x & 0x00FF00FFu) << 8);
  return (x >> 16) | (x << 16);
}

// Sobol dimension 1 (dimension 0 is reverse_bits(i)): the generator matrix of x + 1, bit k
// of i contributing column k (v_0 = 2^31, v_k+1 = v_k ^ v_k >> 1).
inline uint32_t sobol_dimension1_bitwise(uint32_t i) {
  uint32_t result = 0;
  for (uint32_t v = 1u << 31; i != 0; i >>= 1, v ^= v >> 1)
    if (i & 1u) result ^= v;
  return result;
}

namespace detail {

// The same matrix one byte of i at a time: the product is linear over XOR, so four lookups
// give it. The indices are Owen-scrambled, i.e. random 32-bit numbers, on which the bitwise
// loop runs 32 times and mispredicts about every other step, three times per camera path.
struct SobolDimension1Bytes {
  uint32_t columns[4][256] = {};
  constexpr SobolDimension1Bytes() {
    uint32_t v[32] = {};
    v[0] = 1u << 31;
    for (int k = 1; k < 32; ++k) v[k] = v[k - 1] ^ (v[k - 1] >> 1);
    for (int byte = 0; byte < 4; ++byte)
      for (int b = 0; b < 256; ++b)
        for (int bit = 0; bit < 8; ++bit)
          if ((b >> bit) & 1) columns[byte][b] ^= v[8 * byte + bit];
  }
};
inline constexpr SobolDimension1Bytes kSobolDimension1Bytes{};

}  // namespace detail

inline uint32_t sobol_dimension1(uint32_t i) {
  const auto& c = detail::kSobolDimension1Bytes.columns;
  return c[0][i & 0xffu] ^ c[1][(i >> 8) & 0xffu] ^ c[2][(i >> 16) & 0xffu] ^ c[3][i >> 24];
}

// Owen scrambling of a bit-reversed value by Laine and Karras' hash (as in Burley 2020):
// each bit is flipped depending only on the bits above it, so nested strata stay strata.
inline uint32_t owen_scramble(uint32_t x, uint32_t seed) {
  x = reverse_bits(x);
  x += seed;
  x ^= x * 0x6c50b47cu;
  x ^= x * 0xb82f1e52u;
  x ^= x * 0xc7afe638u;
  x ^= x * 0x8d22f6e6u;
  return reverse_bits(x);
}

inline float to_unit_float(uint32_t x) {
  return float(x >> 8) * 0x1p-24f;  // 24 bits: exactly representable, < 1
}

// Point `index` of a scrambled (0,2)-sequence in [0,1)^2; each `key` gives an independent
// randomisation (used for the pixel position and, with other keys, for the first bounce's
// light and BRDF samples: Burley's "padding" of 2D sequences by index shuffling).
inline glm::vec2 pixel_sample(uint32_t index, uint64_t key) {
  const uint32_t seed_index = uint32_t(key), seed_x = uint32_t(key >> 32);
  const uint32_t seed_y = seed_index * 0x9E3779B9u ^ seed_x;
  // Owen-scrambling the index shuffles which points a prefix of the samples takes
  // without breaking the stratification of a power-of-two count.
  const uint32_t i = owen_scramble(index, seed_index);
  return {to_unit_float(owen_scramble(reverse_bits(i), seed_x)), to_unit_float(owen_scramble(sobol_dimension1(i), seed_y))};
}

// Point `index` of a scrambled van der Corput sequence in [0,1): stratified in 1D.
inline float stratified_1d(uint32_t index, uint64_t key) {
  const uint32_t i = owen_scramble(index, uint32_t(key));
  return to_unit_float(owen_scramble(reverse_bits(i), uint32_t(key >> 32)));
}

}  // namespace phyir::render
