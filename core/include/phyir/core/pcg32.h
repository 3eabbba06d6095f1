#pragma once
// The toolkit's one random number generator: PCG32 (O'Neill 2014) with its own
// integer-to-float mappings. Small state, good statistics, and identical results on every
// platform (std::uniform_real_distribution is not: each standard library maps bits
// differently), so rooms, renders and datasets are reproducible everywhere.
#include <glm/glm.hpp>

#include <cstdint>
#include <vector>

namespace phyir {

// splitmix64 (Steele, Lea, Flood 2014) finaliser: mixes seeds so that neighbouring seeds,
// pixels or room indices give unrelated streams.
inline uint64_t mix64(uint64_t x) {
  x += 0x9E3779B97F4A7C15ull;
  x = (x ^ (x >> 30)) * 0xBF58476D1CE4E5B9ull;
  x = (x ^ (x >> 27)) * 0x94D049BB133111EBull;
  return x ^ (x >> 31);
}

class Pcg32 {
 public:
  Pcg32() = default;
  Pcg32(uint64_t seed, uint64_t stream) { reseed(seed, stream); }

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
    return (xorshifted >> rot) | (xorshifted << ((32u - rot) & 31u));
  }

  // [0, 1) from the top 24 bits: every result is an exact float and 1.0 never occurs.
  float next_float() { return static_cast<float>(next_u32() >> 8) * 0x1p-24f; }
  glm::vec2 next_2d() {
    const float a = next_float();  // its own statement: argument order is unspecified
    return glm::vec2(a, next_float());
  }

  float uniform() { return next_float(); }
  float uniform(float lo, float hi) { return lo + (hi - lo) * next_float(); }
  bool chance(float p) { return next_float() < p; }

  // [0, n) without modulo bias: rejects the incomplete last block of 2^32.
  uint32_t below(uint32_t n) {
    const uint32_t limit = static_cast<uint32_t>(-n) % n;  // 2^32 mod n
    for (;;) {
      const uint32_t r = next_u32();
      if (r >= limit) return r % n;
    }
  }

  template <typename T>
  const T& pick(const std::vector<T>& options) {
    return options[below(static_cast<uint32_t>(options.size()))];
  }

 private:
  uint64_t state_ = 0x853c49e6748fea9bull;
  uint64_t inc_ = 0xda3e39cb94b95bdbull;
};

}  // namespace phyir
