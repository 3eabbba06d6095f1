// Doors and windows of an apartment: a door graph that reaches every room from the
// entrance, and windows in the outside walls of every room but the corridor.
#include <algorithm>
#include <cmath>

#include "generator/apartment/apartment_steps.h"

namespace phyir::scenes {

namespace {

constexpr float kEdgeTolerance = 1e-4f;
constexpr int kPlacementTries = 12;

// A straight piece of wall a hole can go through: at `at` across `wall_axis`'s normal,
// running over [from, to] along it, `thickness` thick, on the side `outward` of `room`.
struct WallPiece {
  int room = -1, other = -1;
  int wall_axis = 0;  // 0: runs along x; 1: runs along z
  float at = 0.0f;    // the wall's face on `room`'s side
  float from = 0.0f, to = 0.0f;
  float thickness = 0.0f;
  glm::vec2 outward{0.0f};
};

// The wall shared by cells a and b, if they touch along a side.
bool shared_wall(const ApartmentPlan& plan, const std::vector<Rect2>& cells, int a, int b, WallPiece* piece) {
  const Rect2& ca = cells[a];
  const Rect2& cb = cells[b];
  for (int across = 0; across < 2; ++across) {
    const int along = 1 - across;
    for (int sign = -1; sign <= 1; sign += 2) {
      const float edge_a = sign > 0 ? ca.max[across] : ca.min[across];
      const float edge_b = sign > 0 ? cb.min[across] : cb.max[across];
      if (std::fabs(edge_a - edge_b) > kEdgeTolerance) continue;
      const float from = std::max(plan.rooms[a].floor.min[along], plan.rooms[b].floor.min[along]);
      const float to = std::min(plan.rooms[a].floor.max[along], plan.rooms[b].floor.max[along]);
      if (to <= from) continue;
      piece->room = a;
      piece->other = b;
      piece->wall_axis = along == 0 ? 0 : 1;
      piece->at = edge_a - sign * 0.5f * plan.interior_wall;
      piece->from = from;
      piece->to = to;
      piece->thickness = plan.interior_wall;
      piece->outward = glm::vec2(0.0f);
      piece->outward[across] = float(sign);
      return true;
    }
  }
  return false;
}

// The outside walls of room r: the sides of its cell on the interior's boundary.
std::vector<WallPiece> outside_walls(const ApartmentPlan& plan, const std::vector<Rect2>& cells, int r) {
  std::vector<WallPiece> pieces;
  for (int across = 0; across < 2; ++across) {
    const int along = 1 - across;
    for (int sign = -1; sign <= 1; sign += 2) {
      const float edge = sign > 0 ? cells[r].max[across] : cells[r].min[across];
      const float boundary = sign > 0 ? plan.interior.max[across] : plan.interior.min[across];
      if (std::fabs(edge - boundary) > kEdgeTolerance) continue;
      WallPiece p;
      p.room = r;
      p.wall_axis = along == 0 ? 0 : 1;
      p.at = edge;
      p.from = plan.rooms[r].floor.min[along];
      p.to = plan.rooms[r].floor.max[along];
      p.thickness = plan.exterior_wall;
      p.outward[across] = float(sign);
      pieces.push_back(p);
    }
  }
  return pieces;
}

WallOpening opening_in(const WallPiece& piece, WallOpeningKind kind, float start, float width, float bottom, float top) {
  WallOpening o;
  o.kind = kind;
  o.room = piece.room;
  o.other = piece.other;
  o.wall_axis = piece.wall_axis;
  o.bottom = bottom;
  o.top = top;
  o.outward = piece.outward;
  const int along = piece.wall_axis == 0 ? 0 : 1, across = 1 - along;
  const float far = piece.at + piece.outward[across] * piece.thickness;
  o.footprint.min[along] = start;
  o.footprint.max[along] = start + width;
  o.footprint.min[across] = std::min(piece.at, far);
  o.footprint.max[across] = std::max(piece.at, far);
  return o;
}

bool clear_of_openings(const ApartmentPlan& plan, const WallOpening& candidate) {
  const Rect2 grown = candidate.footprint.inset(-kMinOpeningMargin);
  for (const WallOpening& o : plan.openings) {
    const bool apart = grown.max.x <= o.footprint.min.x || o.footprint.max.x <= grown.min.x ||
                       grown.max.y <= o.footprint.min.y || o.footprint.max.y <= grown.min.y;
    if (!apart) return false;
  }
  return true;
}

// Cuts a hole of `width` at a random place along the piece, clear of the wall's ends and of
// other openings. The width shrinks to what the piece has room for, down to `min_width`.
bool try_cut(ApartmentPlan& plan, const WallPiece& piece, WallOpeningKind kind, float width, float min_width, float bottom,
             float top, Pcg32& rng) {
  const float lo = piece.from + kMinOpeningMargin, hi = piece.to - kMinOpeningMargin;
  width = std::min(width, hi - lo);
  if (width < min_width) return false;
  for (int t = 0; t < kPlacementTries; ++t) {
    const WallOpening o = opening_in(piece, kind, rng.uniform(lo, hi - width), width, bottom, top);
    if (!clear_of_openings(plan, o)) continue;
    plan.openings.push_back(o);
    return true;
  }
  return false;
}

int index_of(const ApartmentPlan& plan, RoomType type) {
  for (size_t r = 0; r < plan.rooms.size(); ++r)
    if (plan.rooms[r].type == type) return static_cast<int>(r);
  return -1;
}

// How much a room prefers to be entered from `from`: a bathroom from the corridor or a
// bedroom, every other room from the corridor or the living room.
int entry_rank(RoomType room, RoomType from) {
  if (from == RoomType::Corridor) return 0;
  if (room == RoomType::Bathroom) return from == RoomType::Bedroom ? 1 : 3;
  return from == RoomType::LivingRoom ? 1 : 2;
}

void cut_doors(ApartmentPlan& plan, const std::vector<Rect2>& cells, Pcg32& rng) {
  const int n = static_cast<int>(plan.rooms.size());
  const int hub = index_of(plan, RoomType::Corridor) >= 0 ? index_of(plan, RoomType::Corridor)
                                                          : index_of(plan, RoomType::LivingRoom);
  std::vector<bool> reached(size_t(n), false);
  reached[size_t(hub)] = true;
  // Grow the reached set by the best-ranked door each time (ties: the lower room index).
  for (int added = 1; added < n; ++added) {
    int best_rank = 1 << 20, best_to = -1;
    WallPiece best;
    for (int to = 0; to < n; ++to) {
      if (reached[size_t(to)]) continue;
      for (int from = 0; from < n; ++from) {
        WallPiece piece;
        if (!reached[size_t(from)] || !shared_wall(plan, cells, from, to, &piece)) continue;
        const int rank = entry_rank(plan.rooms[to].type, plan.rooms[from].type) * 64 + to;
        if (piece.to - piece.from < 0.8f + 2.0f * kMinOpeningMargin || rank >= best_rank) continue;
        best_rank = rank, best_to = to, best = piece;
      }
    }
    if (best_to < 0) break;  // unreachable rooms are reported by the plan's checks
    reached[size_t(best_to)] = true;
    try_cut(plan, best, WallOpeningKind::Door, rng.uniform(0.8f, 0.9f), 0.8f, 0.0f, kDoorHeight, rng);
  }
  // An open passage between the living room and the kitchen when they touch.
  WallPiece piece;
  const int living = index_of(plan, RoomType::LivingRoom), kitchen = index_of(plan, RoomType::Kitchen);
  if (kitchen >= 0 && shared_wall(plan, cells, living, kitchen, &piece) && rng.chance(0.6f))
    try_cut(plan, piece, WallOpeningKind::Door, rng.uniform(1.2f, 1.8f), 0.8f, 0.0f, kDoorHeight, rng);
  // The entrance, from outside into the hub, or the living room if the hub has no room.
  for (int room : {hub, living}) {
    bool entered = false;
    for (const WallPiece& p : outside_walls(plan, cells, room))
      if ((entered = try_cut(plan, p, WallOpeningKind::Door, rng.uniform(0.9f, 1.0f), 0.85f, 0.0f, kDoorHeight, rng))) break;
    if (entered) break;
  }
}

void cut_windows(ApartmentPlan& plan, const std::vector<Rect2>& cells, Pcg32& rng) {
  const float top = std::min(2.25f, plan.height - 0.25f);
  for (size_t r = 0; r < plan.rooms.size(); ++r) {
    const RoomType type = plan.rooms[r].type;
    if (type == RoomType::Corridor || (type == RoomType::Bathroom && rng.chance(0.4f))) continue;
    const int wanted = type == RoomType::LivingRoom ? 2 : 1;
    int cut = 0;
    for (const WallPiece& piece : outside_walls(plan, cells, static_cast<int>(r))) {
      if (cut == wanted) break;
      if (type == RoomType::Bathroom) {
        cut += try_cut(plan, piece, WallOpeningKind::Window, rng.uniform(0.5f, 0.8f), 0.45f, 1.3f, top, rng);
        continue;
      }
      const bool french = type == RoomType::LivingRoom && rng.chance(0.3f);
      const float width = type == RoomType::LivingRoom ? rng.uniform(1.2f, 2.4f) : rng.uniform(0.9f, 1.6f);
      cut += try_cut(plan, piece, WallOpeningKind::Window, width, 0.6f, french ? 0.0f : rng.uniform(0.8f, 1.0f), top, rng);
    }
  }
}

}  // namespace

void cut_openings(ApartmentPlan& plan, const std::vector<Rect2>& cells, Pcg32& rng) {
  cut_doors(plan, cells, rng);
  cut_windows(plan, cells, rng);
}

}  // namespace phyir::scenes
