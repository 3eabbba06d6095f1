#pragma once
// The room generator's random numbers. Rooms must be byte-identical on every platform, and
// std::uniform_real_distribution is not (each standard library maps bits differently), so
// the generator is PCG32 (O'Neill 2014) with its own integer-to-float mappings.
#include <cstdint>
#include <vector>

namespace phyir::scenes {

// splitmix64 (Steele, Lea, Flood 2014): mixes seeds so neighbouring seeds and room indices
// give unrelated streams.
inline uint64_t splitmix64(uint64_t x) {
  x += 0x9E3779B97F4A7C15ull;
  x = (x ^ (x >> 30)) * 0xBF58476D1CE4E5B9ull;
  x = (x ^ (x >> 27)) * 0x94D049BB133111EBull;
  return x ^ (x >> 31);
}

// Each concern of a room (shell, materials, furniture, ...) draws from its own stream, so
// changing how furniture is placed does not change the wall colours.
enum class RoomStream : uint64_t { Shell = 1, Materials, Furniture, Viewpoints, Textures };

class Pcg32 {
 public:
  Pcg32(uint64_t seed, uint64_t stream) : inc_((stream << 1u) | 1u) {
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

  // [0, 1) from the top 24 bits: every result is an exact float.
  float uniform() { return static_cast<float>(next_u32() >> 8) * 0x1p-24f; }
  float uniform(float lo, float hi) { return lo + (hi - lo) * uniform(); }
  bool chance(float p) { return uniform() < p; }

  // [0, n) without modulo bias: reject the incomplete last block of 2^32.
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
  uint64_t state_ = 0;
  uint64_t inc_;
};

// The generator for one concern of room (seed, index, preset).
inline Pcg32 room_rng(uint64_t seed, int index, int preset, RoomStream stream) {
  const uint64_t room = splitmix64(seed ^ splitmix64(static_cast<uint64_t>(index) * 4u +
                                                     static_cast<uint64_t>(preset)));
  return Pcg32(room, static_cast<uint64_t>(stream));
}

}  // namespace phyir::scenes
