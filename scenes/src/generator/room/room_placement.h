#pragma once
// Puts objects built in their own frame (room_furniture.h) into the room by rejection
// sampling: a spot is taken when the object stays inside the walls and keeps a gap to every
// object already placed. Failing to fit is not an error: the room just has one piece less.
#include <vector>

#include "generator/room/room_rng.h"
#include "phyir/scenes/room_layout.h"

namespace phyir::scenes {

class RoomPlacer {
 public:
  RoomPlacer(const RoomShell& shell, std::vector<RoomObject>& objects, Pcg32& rng);

  // Anywhere on the floor, any quarter turn.
  bool place_on_floor(const RoomObject& local);
  // Back (local -z) against a wall, facing into the room. Works for floor pieces and wall items.
  bool place_against_wall(const RoomObject& local);
  // Under the ceiling; ceiling objects keep `spacing` between each other to spread the light.
  bool place_on_ceiling(const RoomObject& local, float spacing);

 private:
  bool try_add(const RoomObject& placed, float spacing_to_same_mount);

  const RoomShell& shell_;
  std::vector<RoomObject>& objects_;
  Pcg32& rng_;
};

}  // namespace phyir::scenes
