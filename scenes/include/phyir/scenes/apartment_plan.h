#pragma once
// The plan of a generated apartment before it is furnished: rooms on a rectangular
// footprint, thick walls, doors between rooms and windows in the outside walls.
// plan_apartment() is a pure function of (seed, index), so tests check the plan without
// writing files. Units and axes follow scene.h: metres, +Y up, right-handed, floor at y = 0.
#include <glm/glm.hpp>

#include <cstdint>
#include <string>
#include <vector>

namespace phyir::scenes {

enum class RoomType { LivingRoom, Kitchen, Bedroom, Bathroom, Corridor };
// "living_room", "kitchen", "bedroom", "bathroom", "corridor".
const char* room_type_name(RoomType type);

// An axis-aligned rectangle in the floor plane: x and z.
struct Rect2 {
  glm::vec2 min{0.0f};
  glm::vec2 max{0.0f};

  glm::vec2 size() const { return max - min; }
  glm::vec2 centre() const { return 0.5f * (min + max); }
  float area() const { return size().x * size().y; }
  bool contains(glm::vec2 p) const { return p.x > min.x && p.x < max.x && p.y > min.y && p.y < max.y; }
  // Shrunk by `margin` on every side (grown when negative).
  Rect2 inset(float margin) const { return {min + margin, max - margin}; }
};

struct ApartmentRoom {
  RoomType type = RoomType::LivingRoom;
  std::string name;  // room_type_name() plus a number when the type repeats: "bedroom_2"
  Rect2 floor;       // the floor between the wall faces
};

enum class WallOpeningKind { Door, Window };

// A hole through a wall, floor-standing for doors (and French windows).
struct WallOpening {
  WallOpeningKind kind = WallOpeningKind::Door;
  int room = -1;   // the room on one side
  int other = -1;  // the room on the other side, -1 for outside
  // 0: the wall runs along x (the hole passes through it along z); 1: the wall runs along z.
  int wall_axis = 0;
  Rect2 footprint;  // the hole in plan: its width along the wall, the wall's thickness across
  float bottom = 0.0f;  // the hole's y range: sill (0 for doors) to lintel
  float top = 2.05f;

  float width() const { return footprint.size()[wall_axis == 0 ? 0 : 1]; }
  float thickness() const { return footprint.size()[wall_axis == 0 ? 1 : 0]; }
  // Unit normal in the floor plane (x, z), pointing from `room` through the hole.
  glm::vec2 outward = glm::vec2(0.0f);
};

struct ApartmentPlan {
  uint64_t seed = 0;
  int index = 0;
  float height = 2.6f;          // floor to ceiling
  float interior_wall = 0.12f;  // thickness of walls between rooms
  float exterior_wall = 0.25f;  // thickness of outside walls
  float slab = 0.2f;            // thickness of the floor and roof slabs
  Rect2 interior;               // the inside faces of the outside walls
  std::vector<ApartmentRoom> rooms;
  std::vector<WallOpening> openings;

  // The outside faces of the outside walls.
  Rect2 outline() const { return interior.inset(-exterior_wall); }
  // The room whose floor contains p (x, z), or -1 (inside a wall, an opening or outside).
  int room_at(glm::vec2 p) const;
  // True where (x, y, z) is wall or slab: inside the outline grown by nothing, in no room's
  // volume and in no opening.
  bool is_solid(const glm::vec3& p) const;
};

// The apartment rules: 2 to 6 rooms; a living room always; then a bedroom, a kitchen, a
// bathroom, a corridor (from 5 rooms on) and a second bedroom; every room reachable from
// the entrance through doors; every room except the corridor and the bathroom has at least
// one window in an outside wall.
constexpr int kMinApartmentRooms = 2;
constexpr int kMaxApartmentRooms = 6;
constexpr float kDoorHeight = 2.05f;
constexpr float kMinOpeningMargin = 0.2f;  // from a wall's end to an opening's side

// `rooms` = 0 draws the count from the seed; otherwise 2..6.
ApartmentPlan plan_apartment(uint64_t seed, int index, int rooms = 0);

}  // namespace phyir::scenes
