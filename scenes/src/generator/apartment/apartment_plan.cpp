// The apartment's floor plan: room types, rows of rooms on a rectangular footprint (with a
// corridor between the rows from five rooms on), then the doors and windows
// (apartment_openings.cpp).
#include "phyir/scenes/apartment_plan.h"

#include <algorithm>
#include <cmath>
#include <numeric>

#include "generator/apartment/apartment_steps.h"
#include "phyir/core/error.h"

namespace phyir::scenes {

const char* room_type_name(RoomType type) {
  switch (type) {
    case RoomType::LivingRoom: return "living_room";
    case RoomType::Kitchen: return "kitchen";
    case RoomType::Bedroom: return "bedroom";
    case RoomType::Bathroom: return "bathroom";
    case RoomType::Corridor: return "corridor";
  }
  return "room";
}

int ApartmentPlan::room_at(glm::vec2 p) const {
  for (size_t r = 0; r < rooms.size(); ++r)
    if (rooms[r].floor.contains(p)) return static_cast<int>(r);
  return -1;
}

bool ApartmentPlan::is_solid(const glm::vec3& p) const {
  const glm::vec2 xz(p.x, p.z);
  if (!outline().contains(xz) || p.y <= -slab || p.y >= height + slab) return false;
  if (p.y <= 0.0f || p.y >= height) return true;  // the floor and roof slabs
  if (room_at(xz) >= 0) return false;
  for (const WallOpening& o : openings)
    if (o.footprint.contains(xz) && p.y > o.bottom && p.y < o.top) return false;
  return true;
}

namespace {

// Room types in the order an apartment gains them, from two rooms to six.
std::vector<RoomType> room_types(int count) {
  static const RoomType kOrder[] = {RoomType::LivingRoom, RoomType::Bedroom, RoomType::Kitchen,
                                    RoomType::Bathroom,   RoomType::Corridor, RoomType::Bedroom};
  return std::vector<RoomType>(kOrder, kOrder + count);
}

float target_area(RoomType type, Pcg32& rng) {
  switch (type) {
    case RoomType::LivingRoom: return rng.uniform(18.0f, 28.0f);
    case RoomType::Kitchen: return rng.uniform(8.0f, 13.0f);
    case RoomType::Bedroom: return rng.uniform(10.0f, 15.0f);
    case RoomType::Bathroom: return rng.uniform(4.0f, 7.0f);
    case RoomType::Corridor: return 0.0f;  // a strip across the footprint, sized by it
  }
  return 10.0f;
}

float min_width(RoomType type) { return type == RoomType::Bathroom ? 1.8f : 2.6f; }

struct Row {
  std::vector<int> rooms;  // indices into the plan's rooms
  float area = 0.0f;
};

// Two rows when there are more than two rooms: the living room starts the first, the rest
// the second; the kitchen moves beside the living room when that balances the rows.
std::vector<Row> split_rows(const std::vector<RoomType>& types, const std::vector<float>& areas) {
  std::vector<Row> rows(types.size() > 2 ? 2 : 1);
  for (size_t r = 0; r < types.size(); ++r) {
    if (types[r] == RoomType::Corridor) continue;
    Row& row = (rows.size() == 1 || types[r] == RoomType::LivingRoom) ? rows[0] : rows[1];
    row.rooms.push_back(static_cast<int>(r));
    row.area += areas[r];
  }
  if (rows.size() < 2) return rows;
  for (size_t k = 0; k < rows[1].rooms.size(); ++k) {
    const int r = rows[1].rooms[k];
    if (types[r] != RoomType::Kitchen || rows[1].area - areas[r] < rows[0].area + areas[r] - 8.0f) continue;
    rows[0].rooms.push_back(r);
    rows[0].area += areas[r];
    rows[1].area -= areas[r];
    rows[1].rooms.erase(rows[1].rooms.begin() + static_cast<long>(k));
    break;
  }
  return rows;
}

// The footprint's width: the rows share it. Narrow enough that every row is at least
// kMinRowDepth deep (a living room alone in its row is not a corridor), wide enough for
// every room's minimum width, which wins.
constexpr float kMinRowDepth = 3.2f;
float footprint_width(const std::vector<Row>& rows, const std::vector<RoomType>& types, float total_area,
                      Pcg32& rng) {
  float width = std::sqrt(total_area * rng.uniform(1.2f, 1.8f));
  float needed = 0.0f;
  for (const Row& row : rows) {
    float row_needed = 0.0f;
    for (int r : row.rooms) row_needed += min_width(types[r]);
    needed = std::max(needed, row_needed);
    width = std::min(width, row.area / kMinRowDepth);
  }
  return std::max(width, needed);
}

// Splits [x0, x1] among the row's rooms in proportion to their areas, each at least its
// minimum width.
std::vector<float> room_widths(const Row& row, const std::vector<RoomType>& types, const std::vector<float>& areas,
                               float width) {
  std::vector<float> widths;
  float spare = width;
  for (int r : row.rooms) spare -= min_width(types[r]);
  float weight = 0.0f;
  for (int r : row.rooms) weight += std::max(areas[r] - min_width(types[r]) * 3.0f, 1.0f);
  for (int r : row.rooms)
    widths.push_back(min_width(types[r]) + spare * std::max(areas[r] - min_width(types[r]) * 3.0f, 1.0f) / weight);
  return widths;
}

}  // namespace

ApartmentPlan plan_apartment(uint64_t seed, int index, int rooms) {
  if (rooms != 0 && (rooms < kMinApartmentRooms || rooms > kMaxApartmentRooms))
    fail("apartment: {} rooms asked for; an apartment has {} to {}", rooms, kMinApartmentRooms, kMaxApartmentRooms);
  Pcg32 rng = apartment_rng(seed, index, ApartmentStream::Layout);
  ApartmentPlan plan;
  plan.seed = seed;
  plan.index = index;
  const int count = rooms != 0 ? rooms : kMinApartmentRooms + static_cast<int>(rng.below(kMaxApartmentRooms - 1));
  plan.height = rng.uniform(2.5f, 2.8f);
  const std::vector<RoomType> types = room_types(count);
  std::vector<float> areas;
  for (RoomType t : types) areas.push_back(target_area(t, rng));
  const std::vector<Row> rows = split_rows(types, areas);
  const float total = std::accumulate(areas.begin(), areas.end(), 0.0f);
  const float width = footprint_width(rows, types, total, rng);
  const bool corridor = std::find(types.begin(), types.end(), RoomType::Corridor) != types.end();
  const float corridor_depth = corridor ? rng.uniform(1.4f, 1.7f) : 0.0f;  // room for the entrance door

  std::vector<Rect2> cells(types.size());
  float z = 0.0f;
  for (size_t k = 0; k < rows.size(); ++k) {
    if (k == 1 && corridor) {
      const int c = static_cast<int>(std::find(types.begin(), types.end(), RoomType::Corridor) - types.begin());
      cells[c] = {{0.0f, z}, {width, z + corridor_depth}};
      z += corridor_depth;
    }
    const float depth = std::clamp(rows[k].area / width, kMinRowDepth, 6.0f);
    const std::vector<float> widths = room_widths(rows[k], types, areas, width);
    float x = 0.0f;
    for (size_t i = 0; i < rows[k].rooms.size(); ++i) {
      cells[rows[k].rooms[i]] = {{x, z}, {x + widths[i], z + depth}};
      x += widths[i];
    }
    z += depth;
  }
  plan.interior = {{0.0f, 0.0f}, {width, z}};
  place_rooms(plan, types, cells, rng);
  Pcg32 openings = apartment_rng(seed, index, ApartmentStream::Openings);
  cut_openings(plan, cells, openings);
  return plan;
}

}  // namespace phyir::scenes
