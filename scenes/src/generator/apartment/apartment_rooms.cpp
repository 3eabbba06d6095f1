// The apartment's rooms placed: mirrored, centred, and inset by the walls between them.
#include <map>
#include <string>

#include "generator/apartment/apartment_steps.h"

namespace phyir::scenes {

namespace {

constexpr float kEdgeTolerance = 1e-4f;

Rect2 mirrored(const Rect2& r, bool mirror_x, bool mirror_z, const Rect2& frame) {
  Rect2 m = r;
  if (mirror_x) m = {{frame.max.x - r.max.x, m.min.y}, {frame.max.x - r.min.x, m.max.y}};
  if (mirror_z) m = {{m.min.x, frame.max.y - r.max.y}, {m.max.x, frame.max.y - r.min.y}};
  return m;
}

// The cell less half an interior wall on each side not on the outside wall.
Rect2 floor_of(const Rect2& cell, const Rect2& interior, float half_wall) {
  Rect2 f = cell;
  for (int a = 0; a < 2; ++a) {
    if (cell.min[a] > interior.min[a] + kEdgeTolerance) f.min[a] += half_wall;
    if (cell.max[a] < interior.max[a] - kEdgeTolerance) f.max[a] -= half_wall;
  }
  return f;
}

}  // namespace

void place_rooms(ApartmentPlan& plan, const std::vector<RoomType>& types, std::vector<Rect2>& cells, Pcg32& rng) {
  const bool mirror_x = rng.chance(0.5f), mirror_z = rng.chance(0.5f);
  const Rect2 frame = plan.interior;
  const glm::vec2 shift = -frame.centre();
  for (Rect2& c : cells) {
    c = mirrored(c, mirror_x, mirror_z, frame);
    c.min += shift;
    c.max += shift;
  }
  plan.interior = {frame.min + shift, frame.max + shift};
  std::map<RoomType, int> seen;
  for (size_t r = 0; r < types.size(); ++r) {
    ApartmentRoom room;
    room.type = types[r];
    const int n = ++seen[types[r]];
    room.name = std::string(room_type_name(types[r])) + (n > 1 ? "_" + std::to_string(n) : "");
    room.floor = floor_of(cells[r], plan.interior, 0.5f * plan.interior_wall);
    plan.rooms.push_back(room);
  }
}

}  // namespace phyir::scenes
