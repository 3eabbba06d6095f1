// Rejection-sampled placement of furniture, wall items and lights.
#include "generator/room/room_placement.h"

#include <algorithm>
#include <cmath>

#include "generator/room/room_furniture.h"

namespace phyir::scenes {

namespace {

constexpr int kAttempts = 100;
constexpr float kObjectGap = 0.05f;       // between any two objects: nothing touches
constexpr float kFloorWallMargin = 0.05f; // free-standing furniture to the walls
constexpr float kBackToWall = 0.01f;      // furniture backed on a wall (skirting-board gap)
constexpr float kWallItemGap = 0.002f;    // mirrors and panels: 2 mm, not coplanar with the wall
constexpr float kCeilingWallMargin = 0.3f;

// Quarter turns that take local +z (an object's front) to the wall's inward normal.
int turns_to_face(glm::vec2 inward) {
  if (inward.x > 0.5f) return 1;
  if (inward.x < -0.5f) return 3;
  return inward.y > 0.5f ? 0 : 2;
}

}  // namespace

RoomPlacer::RoomPlacer(const RoomShell& shell, std::vector<RoomObject>& objects, Pcg32& rng)
    : shell_(shell), objects_(objects), rng_(rng) {}

bool RoomPlacer::try_add(const RoomObject& placed, float spacing_to_same_mount) {
  const Box3& b = placed.bounds;
  if (b.min.y < 0.0f || b.max.y > shell_.height) return false;
  if (!shell_.contains({b.min.x, b.min.z}, {b.max.x, b.max.z}, 0.0f)) return false;
  for (const RoomObject& other : objects_) {
    const float gap = other.mount == placed.mount ? std::max(kObjectGap, spacing_to_same_mount) : kObjectGap;
    if (b.overlaps(other.bounds, gap)) return false;
  }
  objects_.push_back(placed);
  return true;
}

bool RoomPlacer::place_on_floor(const RoomObject& local) {
  for (int attempt = 0; attempt < kAttempts; ++attempt) {
    const int turns = static_cast<int>(rng_.below(4));
    const RoomObject turned = transformed(local, turns, glm::vec3(0.0f));
    const glm::vec3 size = turned.bounds.size();
    const float x = rng_.uniform(-0.5f * shell_.width, 0.5f * shell_.width);
    const float z = rng_.uniform(-0.5f * shell_.depth, 0.5f * shell_.depth);
    const glm::vec2 lo(x - 0.5f * size.x, z - 0.5f * size.z), hi(x + 0.5f * size.x, z + 0.5f * size.z);
    if (!shell_.contains(lo, hi, kFloorWallMargin)) continue;
    const glm::vec3 centre = turned.bounds.centre();
    if (try_add(transformed(turned, 0, {x - centre.x, 0.0f, z - centre.z}), 0.0f)) return true;
  }
  return false;
}

bool RoomPlacer::place_against_wall(const RoomObject& local) {
  const std::vector<glm::vec2> corners = shell_.outline();
  const float gap = local.mount == Mount::Wall ? kWallItemGap : kBackToWall;
  for (int attempt = 0; attempt < kAttempts; ++attempt) {
    const int wall = static_cast<int>(rng_.below(static_cast<uint32_t>(corners.size())));
    const glm::vec2 a = corners[wall];
    const glm::vec2 b = corners[(wall + 1) % corners.size()];
    const glm::vec2 inward = shell_.wall_inward_normal(wall);
    const RoomObject turned = transformed(local, turns_to_face(inward), glm::vec3(0.0f));

    const int across = std::abs(inward.x) > 0.5f ? 0 : 2;  // the wall's normal axis
    const int along = 2 - across;
    const float wall_at = across == 0 ? a.x : a.y;
    const float lo = std::min(across == 0 ? a.y : a.x, across == 0 ? b.y : b.x);
    const float hi = std::max(across == 0 ? a.y : a.x, across == 0 ? b.y : b.x);
    const float extent = turned.bounds.size()[along];
    if (hi - lo < extent + 0.02f) continue;
    const float t = rng_.uniform(lo + 0.5f * extent + 0.01f, hi - 0.5f * extent - 0.01f);

    glm::vec3 offset(0.0f);
    const float inward_sign = across == 0 ? inward.x : inward.y;
    offset[across] = inward_sign > 0.0f ? wall_at + gap - turned.bounds.min[across]
                                        : wall_at - gap - turned.bounds.max[across];
    offset[along] = t - turned.bounds.centre()[along];
    if (try_add(transformed(turned, 0, offset), 0.0f)) return true;
  }
  return false;
}

bool RoomPlacer::place_on_ceiling(const RoomObject& local, float spacing) {
  for (int attempt = 0; attempt < kAttempts; ++attempt) {
    const int turns = static_cast<int>(rng_.below(2));
    const RoomObject turned = transformed(local, turns, glm::vec3(0.0f));
    const glm::vec3 size = turned.bounds.size();
    const float x = rng_.uniform(-0.5f * shell_.width, 0.5f * shell_.width);
    const float z = rng_.uniform(-0.5f * shell_.depth, 0.5f * shell_.depth);
    const glm::vec2 lo(x - 0.5f * size.x, z - 0.5f * size.z), hi(x + 0.5f * size.x, z + 0.5f * size.z);
    if (!shell_.contains(lo, hi, kCeilingWallMargin)) continue;
    const glm::vec3 centre = turned.bounds.centre();
    if (try_add(transformed(turned, 0, {x - centre.x, 0.0f, z - centre.z}), spacing)) return true;
  }
  return false;
}

}  // namespace phyir::scenes
