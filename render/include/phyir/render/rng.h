#pragma once
// Deterministic random numbers. Every pixel sample gets its own stream derived from
// (seed, pixel, sample), so images do not depend on thread count or tile order.
#include <cstdint>

#include <glm/glm.hpp>

namespace phyir::render {

// splitmix64 finaliser: a strong 64-bit mix used to derive stream seeds.
inline uint64_t mix64(uint64_t x) {
  x += 0x9E3779B97F4A7C15ull;
  x = (x ^ (x >> 30)) * 0xBF58476D1CE4E5B9ull;
  x = (x ^ (x >> 27)) * 0x94D049BB133111EBull;
  return x ^ (x >> 31);
}

// PCG32 (O'Neill 2014): small state, good statistics, identical on every platform.
class Rng {
 public:
  Rng() = default;
  Rng(uint64_t seed, uint64_t stream) { reseed(seed, stream); }
  void reseed(uint64_t seed, uint64_t stream) {
    state_ = 0u;
    inc_ = (stream << 1u) | 1u;
    next_u32();
    state_ += seed;
    next_u32();
  }
  uint32_t next_u32() {
    const uint64_t old = state_;
    state_ = old * 6364136223846793005ull + inc_;
    const uint32_t xorshifted = static_cast<uint32_t>(((old >> 18u) ^ old) >> 27u);
    const uint32_t rot = static_cast<uint32_t>(old >> 59u);
    return (xorshifted >> rot) | (xorshifted << ((-rot) & 31u));
  }
  // Uniform in [0, 1): 24 random bits, so 1.0 is never returned.
  float next_float() { return static_cast<float>(next_u32() >> 8) * 0x1p-24f; }
  glm::vec2 next_2d() {
    const float a = next_float();
    return glm::vec2(a, next_float());
  }

 private:
  uint64_t state_ = 0x853c49e6748fea9bull;
  uint64_t inc_ = 0xda3e39cb94b95bdbull;
};

// The stream for one pixel sample of one render.
inline Rng pixel_sample_rng(uint64_t seed, uint64_t pixel_index, uint64_t sample_index) {
  return Rng(mix64(seed ^ mix64(pixel_index)), mix64(sample_index) ^ pixel_index);
}

}  // namespace phyir::render
