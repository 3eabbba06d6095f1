// Placement moves inside one room (apartment_placer.h).
#include "generator/apartment/apartment_placer.h"

#include <algorithm>
#include <cmath>

namespace phyir::scenes {

namespace {

constexpr int kTries = 24;
constexpr float kWallGap = 0.02f;     // between a piece's back and its wall
constexpr float kClearance = 0.01f;   // between pieces' boxes
constexpr float kDoorWalkway = 0.9f;  // kept free in front of a door
constexpr float kWindowLight = 0.35f; // kept free in front of a window, above its sill

// Wall w of a room: 0 at -z, 1 at +x, 2 at +z, 3 at -x; inward normal, and the quarter
// turns that face a piece's front (+Z) along it.
glm::vec3 inward(int wall) {
  static const glm::vec3 kIn[4] = {{0, 0, 1}, {-1, 0, 0}, {0, 0, -1}, {1, 0, 0}};
  return kIn[wall];
}
int turns_facing(const glm::vec3& dir) {
  if (dir.z > 0.5f) return 0;
  if (dir.x > 0.5f) return 1;
  if (dir.z < -0.5f) return 2;
  return 3;
}
int along_axis(int wall) { return wall % 2 == 0 ? 0 : 2; }  // world x or z

}  // namespace

RoomPlacer::RoomPlacer(const ApartmentPlan& plan, int room, std::vector<PlacedAsset>& items, AssetModelCache& models,
                       Pcg32& rng)
    : plan_(plan), room_(room), floor_(plan.rooms[size_t(room)].floor), items_(items), models_(models), rng_(rng) {
  wall_of_.assign(items_.size(), -1);
  add_keepouts();
}

void RoomPlacer::add_keepouts() {
  for (const WallOpening& o : plan_.openings) {
    if (o.room != room_ && o.other != room_) continue;
    const glm::vec2 into = o.room == room_ ? -o.outward : o.outward;  // from the hole into this room
    const int across = o.wall_axis == 0 ? 1 : 0, along = 1 - across;
    const bool walkway = o.kind == WallOpeningKind::Door || o.bottom < 0.3f;
    const float depth = walkway ? kDoorWalkway : kWindowLight;
    const float face = into[across] > 0.0f ? o.footprint.max[across] : o.footprint.min[across];
    Box3 box;
    box.min[along == 0 ? 0 : 2] = o.footprint.min[along] - 0.15f;
    box.max[along == 0 ? 0 : 2] = o.footprint.max[along] + 0.15f;
    box.min[across == 0 ? 0 : 2] = std::min(face, face + into[across] * depth);
    box.max[across == 0 ? 0 : 2] = std::max(face, face + into[across] * depth);
    box.min.y = walkway ? 0.0f : std::max(0.0f, o.bottom - 0.1f);
    box.max.y = walkway ? plan_.height : o.top;
    keepouts_.push_back(box);
  }
}

PlacedAsset RoomPlacer::make(const AssetEntry* entry, const std::string& role) const {
  PlacedAsset p;
  p.entry = entry;
  p.role = role;
  p.room = room_;
  p.position.y = entry->elevation_m;
  return p;
}

bool RoomPlacer::is_free(const PlacedAsset& piece, int may_overlap) const {
  const Box3 box = piece.bounds();
  if (box.min.x < floor_.min.x || box.max.x > floor_.max.x || box.min.z < floor_.min.y || box.max.z > floor_.max.y ||
      box.max.y > plan_.height + 1e-4f)
    return false;
  for (const Box3& k : keepouts_)
    if (box.overlaps(k, 0.0f)) return false;
  for (size_t j = 0; j < items_.size(); ++j) {
    const PlacedAsset& other = items_[j];
    if (other.room != room_) continue;
    const bool allowed = int(j) == may_overlap;  // a host, or a table a chair tucks under
    if (!box.overlaps(other.bounds(), allowed ? 0.0f : kClearance)) continue;
    if (!allowed) return false;
    if (pieces_interpenetrate(piece, other, models_)) return false;
  }
  return true;
}

int RoomPlacer::try_add(PlacedAsset piece, int may_overlap) {
  if (!is_free(piece, may_overlap)) return -1;
  items_.push_back(std::move(piece));
  wall_of_.push_back(-1);
  return static_cast<int>(items_.size()) - 1;
}

int RoomPlacer::wall_of(int piece) const { return piece >= 0 && size_t(piece) < wall_of_.size() ? wall_of_[piece] : -1; }

// The room's extent along wall w: its start and end coordinates.
glm::vec2 RoomPlacer::wall_extent(int w) const {
  return along_axis(w) == 0 ? glm::vec2(floor_.min.x, floor_.max.x) : glm::vec2(floor_.min.y, floor_.max.y);
}

int RoomPlacer::try_on_wall(const AssetEntry* entry, const std::string& role, int w, float along) {
  PlacedAsset p = make(entry, role);
  p.quarter_turns = turns_facing(inward(w));
  const float back = w == 0 ? floor_.min.y : w == 1 ? floor_.max.x : w == 2 ? floor_.max.y : floor_.min.x;
  const float across = back + (w == 0 || w == 3 ? 1.0f : -1.0f) * (0.5f * entry->size_m.z + kWallGap);
  const bool along_x = along_axis(w) == 0;
  p.position.x = along_x ? along : across;
  p.position.z = along_x ? across : along;
  const int index = try_add(p);
  if (index >= 0) wall_of_[size_t(index)] = w;
  return index;
}

int RoomPlacer::against_wall(const AssetEntry* entry, const std::string& role, int wall) {
  if (!entry) return -1;
  for (int t = 0; t < kTries; ++t) {
    const int w = wall >= 0 && t < kTries / 2 ? wall : int(rng_.below(4));
    const glm::vec2 extent = wall_extent(w);
    const float lo = extent.x + 0.5f * entry->size_m.x, hi = extent.y - 0.5f * entry->size_m.x;
    if (hi < lo) continue;
    const int index = try_on_wall(entry, role, w, rng_.uniform(lo, hi));
    if (index >= 0) return index;
  }
  return -1;
}

int RoomPlacer::in_corner(const AssetEntry* entry, const std::string& role) {
  if (!entry) return -1;
  for (int t = 0; t < kTries; ++t) {
    const int w = int(rng_.below(4));
    const bool high_end = rng_.chance(0.5f);
    const glm::vec2 extent = wall_extent(w);
    const float half = 0.5f * entry->size_m.x + kWallGap;
    const int index = try_on_wall(entry, role, w, high_end ? extent.y - half : extent.x + half);
    if (index >= 0) return index;
  }
  return -1;
}

int RoomPlacer::in_front_of(int other, const AssetEntry* entry, const std::string& role, float gap) {
  if (!entry || other < 0) return -1;
  const PlacedAsset host = items_[size_t(other)];
  PlacedAsset p = make(entry, role);
  p.quarter_turns = host.quarter_turns;
  const glm::vec3 f = host.front();
  p.position.x = host.position.x + f.x * (0.5f * host.size().z + gap + 0.5f * entry->size_m.z);
  p.position.z = host.position.z + f.z * (0.5f * host.size().z + gap + 0.5f * entry->size_m.z);
  return try_add(p);
}

int RoomPlacer::beside(int bed, const AssetEntry* entry, const std::string& role) {
  if (!entry || bed < 0) return 0;
  const PlacedAsset host = items_[size_t(bed)];
  const glm::vec3 f = host.front();
  const glm::vec3 side(f.z, 0.0f, -f.x);  // perpendicular to the front, in the floor plane
  int placed = 0;
  for (float sign : {-1.0f, 1.0f}) {
    PlacedAsset p = make(entry, role);
    p.quarter_turns = host.quarter_turns;
    const float offset = 0.5f * host.size().x + 0.5f * entry->size_m.x + 0.03f;
    // Backs level with the bed's head.
    const float back_shift = -0.5f * host.size().z + 0.5f * entry->size_m.z;
    p.position.x = host.position.x + sign * side.x * offset + f.x * back_shift;
    p.position.z = host.position.z + sign * side.z * offset + f.z * back_shift;
    placed += try_add(p) >= 0;
  }
  return placed;
}

int RoomPlacer::around(int table, const AssetEntry* entry, const std::string& role, int most) {
  if (!entry || table < 0) return 0;
  const Box3 t = items_[size_t(table)].bounds();
  int placed = 0;
  // Sides as (outward normal, length along the side); the longer sides first.
  const bool x_long = t.size().x >= t.size().z;
  const glm::vec3 normals[4] = {{0, 0, 1}, {0, 0, -1}, {1, 0, 0}, {-1, 0, 0}};
  for (int k = 0; k < 4 && placed < most; ++k) {
    const glm::vec3 n = normals[x_long ? k : (k + 2) % 4];
    const float length = n.x != 0.0f ? t.size().z : t.size().x;
    const int count = std::min(most - placed, int(length / std::max(entry->size_m.x + 0.1f, 0.5f)));
    for (int c = 0; c < count; ++c) {
      const float along = (float(c) + 0.5f) / float(count) - 0.5f;
      for (float tuck : {0.25f, 0.15f, 0.05f, -0.02f}) {
        PlacedAsset p = make(entry, role);
        p.quarter_turns = turns_facing(-n);
        const glm::vec3 edge = t.centre() + n * (0.5f * (n.x != 0.0f ? t.size().x : t.size().z));
        const glm::vec3 pos = edge + n * (0.5f * entry->size_m.z - tuck) +
                              glm::vec3(n.z, 0.0f, n.x) * (along * length);
        p.position.x = pos.x;
        p.position.z = pos.z;
        if (try_add(p, table) >= 0) {
          ++placed;
          break;
        }
      }
    }
  }
  return placed;
}

int RoomPlacer::on_top(int host, const AssetEntry* entry, const std::string& role) {
  if (!entry || host < 0) return -1;
  const PlacedAsset h = items_[size_t(host)];
  if (h.entry->drop_on_top_elevation < 0.0f) return -1;
  const Box3 hb = h.bounds();
  for (int t = 0; t < kTries / 2; ++t) {
    PlacedAsset p = make(entry, role);
    p.host = host;
    p.quarter_turns = h.quarter_turns;
    const glm::vec3 half = 0.5f * (p.bounds().max - p.bounds().min) + glm::vec3(0.02f);
    if (hb.max.x - hb.min.x < 2.0f * half.x || hb.max.z - hb.min.z < 2.0f * half.z) return -1;
    p.position.x = rng_.uniform(hb.min.x + half.x, hb.max.x - half.x);
    p.position.z = rng_.uniform(hb.min.z + half.z, hb.max.z - half.z);
    p.position.y = h.position.y + h.size().y * h.entry->drop_on_top_elevation + 0.002f;
    const int index = try_add(p, host);
    if (index >= 0) return index;
  }
  return -1;
}

int RoomPlacer::on_ceiling(const AssetEntry* entry, const std::string& role) {
  if (!entry) return -1;
  PlacedAsset p = make(entry, role);
  const glm::vec2 c = floor_.centre();
  p.position = glm::vec3(c.x, plan_.height - entry->size_m.y, c.y);  // hanging from the ceiling
  p.quarter_turns = floor_.size().x >= floor_.size().y ? 0 : 1;
  return try_add(p);
}

int RoomPlacer::in_middle(const AssetEntry* entry, const std::string& role) {
  if (!entry) return -1;
  for (int t = 0; t < kTries; ++t) {
    PlacedAsset p = make(entry, role);
    const glm::vec2 c = floor_.centre() + glm::vec2(rng_.uniform(-0.4f, 0.4f), rng_.uniform(-0.4f, 0.4f));
    p.position.x = c.x;
    p.position.z = c.y;
    // The piece's width along the room's longer side.
    p.quarter_turns = floor_.size().x >= floor_.size().y ? 0 : 1;
    const int index = try_add(p);
    if (index >= 0) return index;
  }
  return -1;
}

}  // namespace phyir::scenes
