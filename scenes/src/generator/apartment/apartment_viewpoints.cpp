// Viewpoints of an apartment: in every room, at eye height (1.2-1.8 m), at least
// kViewpointClearance from the walls and from every piece's box, spread out (the rules of
// room_layout.h for single rooms). The living room's most open one is the glTF camera.
#include <algorithm>
#include <cmath>
#include <limits>

#include "generator/apartment/apartment_steps.h"
#include "phyir/scenes/apartment_generator.h"

namespace phyir::scenes {

namespace {

constexpr int kSamplesPerRoom = 400;
constexpr int kViewpointsPerRoom = 8;
constexpr float kMinSpacing = 0.5f;  // between two viewpoints of a room

float to_millimetres(float metres) { return std::round(metres * 1000.0f) / 1000.0f; }

// Distance from p to the nearest wall of its room or piece in it: how open the view is.
float clearance(const ApartmentPlan& plan, const std::vector<PlacedAsset>& items, int room, const glm::vec3& p) {
  const Rect2& f = plan.rooms[size_t(room)].floor;
  float nearest = std::min({p.x - f.min.x, f.max.x - p.x, p.z - f.min.y, f.max.y - p.z});
  for (const PlacedAsset& item : items)
    if (item.room == room) nearest = std::min(nearest, item.bounds().distance_to(p));
  return nearest;
}

}  // namespace

std::vector<ApartmentViewpoint> plan_apartment_viewpoints(const ApartmentPlan& plan,
                                                          const std::vector<PlacedAsset>& items) {
  Pcg32 rng = apartment_rng(plan.seed, plan.index, ApartmentStream::Viewpoints);
  std::vector<ApartmentViewpoint> out;
  for (size_t r = 0; r < plan.rooms.size(); ++r) {
    const Rect2& f = plan.rooms[r].floor;
    std::vector<ApartmentViewpoint> room_points;
    for (int s = 0; s < kSamplesPerRoom && int(room_points.size()) < kViewpointsPerRoom; ++s) {
      const glm::vec3 p(to_millimetres(rng.uniform(f.min.x, f.max.x)),
                        to_millimetres(rng.uniform(kViewpointMinHeight, kViewpointMaxHeight)),
                        to_millimetres(rng.uniform(f.min.y, f.max.y)));
      const float open = clearance(plan, items, int(r), p);
      if (open < kViewpointClearance) continue;
      const bool spaced = std::none_of(room_points.begin(), room_points.end(), [&](const ApartmentViewpoint& v) {
        return glm::length(v.position - p) < kMinSpacing;
      });
      if (spaced) room_points.push_back({int(r), p, open});
    }
    out.insert(out.end(), room_points.begin(), room_points.end());
  }
  return out;
}

}  // namespace phyir::scenes
