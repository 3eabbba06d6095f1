// The apartment planner's rules, checked over many seeds: rooms that tile the footprint
// without overlapping, doors that reach every room from outside, windows in outside walls,
// and a shell that is a closed, consistently oriented surface.
#include <gtest/gtest.h>

#include <map>
#include <queue>
#include <set>
#include <tuple>

#include "phyir/scenes/apartment_plan.h"
#include "phyir/scenes/apartment_shell.h"

namespace phyir::scenes {
namespace {

constexpr int kSeeds = 60;

bool overlap(const Rect2& a, const Rect2& b) {
  return a.min.x < b.max.x && b.min.x < a.max.x && a.min.y < b.max.y && b.min.y < a.max.y;
}

// The room (or -1 outside the building, -2 inside a wall) a little way beyond the opening
// on each side.
std::pair<int, int> sides_of(const ApartmentPlan& plan, const WallOpening& o) {
  const glm::vec2 c = o.footprint.centre();
  const float reach = 0.5f * o.thickness() + 0.05f;
  auto at = [&](glm::vec2 p) { return plan.outline().contains(p) ? plan.room_at(p) == -1 ? -2 : plan.room_at(p) : -1; };
  return {at(c - reach * o.outward), at(c + reach * o.outward)};
}

TEST(ApartmentPlan, RoomsTileTheFootprintWithoutOverlap) {
  for (int rooms = kMinApartmentRooms; rooms <= kMaxApartmentRooms; ++rooms)
    for (int seed = 1; seed <= kSeeds; ++seed) {
      const ApartmentPlan plan = plan_apartment(uint64_t(seed), 0, rooms);
      ASSERT_EQ(plan.rooms.size(), size_t(rooms));
      EXPECT_EQ(plan.rooms[0].type, RoomType::LivingRoom);
      float area = 0.0f;
      for (size_t a = 0; a < plan.rooms.size(); ++a) {
        const Rect2& f = plan.rooms[a].floor;
        EXPECT_GE(f.min.x, plan.interior.min.x - 1e-5f);
        EXPECT_LE(f.max.y, plan.interior.max.y + 1e-5f);
        EXPECT_GE(std::min(f.size().x, f.size().y), 1.2f) << plan.rooms[a].name << " seed " << seed;
        area += f.area();
        for (size_t b = a + 1; b < plan.rooms.size(); ++b)
          EXPECT_FALSE(overlap(f, plan.rooms[b].floor)) << plan.rooms[a].name << " / " << plan.rooms[b].name;
      }
      // The walls between rooms take the rest (less than 12% of the interior).
      EXPECT_GT(area, 0.88f * plan.interior.area()) << "seed " << seed;
      EXPECT_LE(area, plan.interior.area() + 1e-3f);
    }
}

TEST(ApartmentPlan, DoorsReachEveryRoomFromOutside) {
  for (int rooms = kMinApartmentRooms; rooms <= kMaxApartmentRooms; ++rooms)
    for (int seed = 1; seed <= kSeeds; ++seed) {
      const ApartmentPlan plan = plan_apartment(uint64_t(seed), 3, rooms);
      std::multimap<int, int> edges;  // room -> room, -1 = outside
      int entrances = 0;
      for (const WallOpening& o : plan.openings) {
        const auto [near, far] = sides_of(plan, o);
        EXPECT_EQ(near, o.room) << "seed " << seed;  // each opening joins what it says it joins
        EXPECT_EQ(far, o.other) << "seed " << seed;
        if (o.kind != WallOpeningKind::Door) continue;
        EXPECT_EQ(o.bottom, 0.0f);
        entrances += o.other == -1;
        edges.insert({o.room, o.other});
        edges.insert({o.other, o.room});
      }
      EXPECT_EQ(entrances, 1) << "seed " << seed;
      std::set<int> reached{-1};
      std::queue<int> todo;
      todo.push(-1);
      while (!todo.empty()) {
        const int r = todo.front();
        todo.pop();
        for (auto [it, end] = edges.equal_range(r); it != end; ++it)
          if (reached.insert(it->second).second) todo.push(it->second);
      }
      EXPECT_EQ(reached.size(), plan.rooms.size() + 1) << rooms << " rooms, seed " << seed;
    }
}

TEST(ApartmentPlan, LivingRoomsBedroomsAndKitchensHaveWindows) {
  for (int seed = 1; seed <= 3 * kSeeds; ++seed) {
    const ApartmentPlan plan = plan_apartment(uint64_t(seed), 1);
    std::vector<int> windows(plan.rooms.size(), 0);
    for (const WallOpening& o : plan.openings) {
      if (o.kind != WallOpeningKind::Window) continue;
      EXPECT_EQ(o.other, -1) << "a window opens to the outside";
      EXPECT_GE(o.width(), 0.45f);
      EXPECT_LT(o.top, plan.height);
      EXPECT_NEAR(o.thickness(), plan.exterior_wall, 1e-5f);
      ++windows[size_t(o.room)];
    }
    for (size_t r = 0; r < plan.rooms.size(); ++r) {
      const RoomType t = plan.rooms[r].type;
      if (t != RoomType::Corridor && t != RoomType::Bathroom) {
        EXPECT_GE(windows[r], 1) << plan.rooms[r].name;
      }
      if (t == RoomType::Corridor) {
        EXPECT_EQ(windows[r], 0);
      }
    }
  }
}

TEST(ApartmentPlan, OpeningsDoNotOverlap) {
  for (int seed = 1; seed <= 3 * kSeeds; ++seed) {
    const ApartmentPlan plan = plan_apartment(uint64_t(seed), 2);
    for (size_t a = 0; a < plan.openings.size(); ++a)
      for (size_t b = a + 1; b < plan.openings.size(); ++b)
        EXPECT_FALSE(overlap(plan.openings[a].footprint.inset(-0.1f), plan.openings[b].footprint)) << "seed " << seed;
  }
}

TEST(ApartmentPlan, SameSeedSamePlanAndRoomCountsVary) {
  std::set<size_t> counts;
  for (int seed = 1; seed <= 40; ++seed) {
    const ApartmentPlan a = plan_apartment(uint64_t(seed), 0), b = plan_apartment(uint64_t(seed), 0);
    ASSERT_EQ(a.rooms.size(), b.rooms.size());
    ASSERT_EQ(a.openings.size(), b.openings.size());
    for (size_t r = 0; r < a.rooms.size(); ++r) EXPECT_EQ(a.rooms[r].floor.min, b.rooms[r].floor.min);
    counts.insert(a.rooms.size());
  }
  EXPECT_EQ(counts.size(), size_t(kMaxApartmentRooms - kMinApartmentRooms + 1));
  EXPECT_THROW(plan_apartment(1, 0, 7), std::exception);
}

// Every directed edge of a closed, consistently oriented surface is matched by its reverse.
TEST(ApartmentShell, IsClosedAndOriented) {
  for (int seed = 1; seed <= 20; ++seed) {
    const ApartmentPlan plan = plan_apartment(uint64_t(seed), 0);
    std::map<std::tuple<float, float, float, float, float, float>, int> directed;
    std::set<std::pair<int, int>> surfaces;
    for (const ShellPiece& piece : mesh_apartment_shell(plan)) {
      surfaces.insert({piece.room, static_cast<int>(piece.surface)});
      for (size_t t = 0; t < piece.indices.size(); t += 3)
        for (int e = 0; e < 3; ++e) {
          const glm::vec3 a = piece.positions[piece.indices[t + e]], b = piece.positions[piece.indices[t + (e + 1) % 3]];
          ++directed[{a.x, a.y, a.z, b.x, b.y, b.z}];
        }
    }
    for (const auto& [edge, count] : directed) {
      const auto& [ax, ay, az, bx, by, bz] = edge;
      const auto reverse = directed.find({bx, by, bz, ax, ay, az});
      ASSERT_NE(reverse, directed.end()) << "open edge, seed " << seed;
      EXPECT_EQ(reverse->second, count);
    }
    for (size_t r = 0; r < plan.rooms.size(); ++r)
      for (ShellSurface s : {ShellSurface::Floor, ShellSurface::Ceiling, ShellSurface::Wall})
        EXPECT_TRUE(surfaces.count({int(r), int(s)})) << plan.rooms[r].name << " " << shell_surface_name(s);
  }
}

TEST(ApartmentShell, FloorsCoverTheRoomsAndFaceUp) {
  const ApartmentPlan plan = plan_apartment(5, 0, 6);
  for (const ShellPiece& piece : mesh_apartment_shell(plan)) {
    if (piece.surface != ShellSurface::Floor) continue;
    float area = 0.0f;
    for (size_t t = 0; t < piece.indices.size(); t += 3) {
      const glm::vec3 a = piece.positions[piece.indices[t]], b = piece.positions[piece.indices[t + 1]],
                      c = piece.positions[piece.indices[t + 2]];
      const glm::vec3 n = glm::cross(b - a, c - a);
      EXPECT_GT(n.y, 0.0f);
      area += 0.5f * glm::length(n);
    }
    // The room's floor, plus the thresholds of its doors.
    EXPECT_GE(area, plan.rooms[size_t(piece.room)].floor.area() - 1e-3f);
    EXPECT_LE(area, plan.rooms[size_t(piece.room)].floor.area() + 1.0f);
  }
}

}  // namespace
}  // namespace phyir::scenes
