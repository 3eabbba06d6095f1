#pragma once
// The room generator's random streams. Rooms must be byte-identical on every platform, so
// the generator draws from the toolkit's PCG32 with its own integer-to-float mappings.
#include <cstdint>

#include "phyir/core/pcg32.h"

namespace phyir::scenes {

// Each concern of a room (shell, materials, furniture, ...) draws from its own stream, so
// changing how furniture is placed does not change the wall colours.
enum class RoomStream : uint64_t { Shell = 1, Materials, Furniture, Viewpoints, Textures };

// The generator for one concern of room (seed, index, preset).
inline Pcg32 room_rng(uint64_t seed, int index, int preset, RoomStream stream) {
  const uint64_t room = mix64(seed ^ mix64(static_cast<uint64_t>(index) * 4u +
                                                     static_cast<uint64_t>(preset)));
  return Pcg32(room, static_cast<uint64_t>(stream));
}

}  // namespace phyir::scenes
