#pragma once
// The steps plan_apartment() runs, in their own files: shared by the planner only.
#include <cstdint>
#include <vector>

#include "phyir/core/pcg32.h"
#include "phyir/scenes/apartment_plan.h"

namespace phyir::scenes {

// Each concern of an apartment draws from its own stream, so changing how windows are cut
// does not move the rooms.
enum class ApartmentStream : uint64_t { Layout = 1, Openings, Materials, Furniture, Lights, Viewpoints };

inline Pcg32 apartment_rng(uint64_t seed, int index, ApartmentStream stream) {
  // 0xA9 keeps apartments' streams apart from the single-room presets' (room_rng.h).
  const uint64_t apartment = mix64(seed ^ mix64(static_cast<uint64_t>(index) * 256u + 0xA9u));
  return Pcg32(apartment, static_cast<uint64_t>(stream));
}

// Mirrors the layout at random, centres it on the origin, and makes each room's floor its
// cell less half an interior wall on every side shared with another cell. `cells` (the
// rooms' rectangles before the walls, in plan.interior) are transformed with it.
void place_rooms(ApartmentPlan& plan, const std::vector<RoomType>& types, std::vector<Rect2>& cells, Pcg32& rng);

// Doors between rooms (every room reachable from the entrance, which opens from outside
// into the corridor or the living room) and windows in outside walls.
void cut_openings(ApartmentPlan& plan, const std::vector<Rect2>& cells, Pcg32& rng);

}  // namespace phyir::scenes
