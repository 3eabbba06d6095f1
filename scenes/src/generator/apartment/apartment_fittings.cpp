// Doors and windows of the library fitted into the plan's openings, as Sweet Home 3D fits
// them into walls: scaled to the hole's width and height, and in depth so that the part of
// the model made for the wall (doorOrWindowWallThickness at doorOrWindowWallDistance) spans
// the wall's thickness. Fronts face the room the opening belongs to.
#include "generator/apartment/apartment_roles.h"
#include "phyir/scenes/apartment_furnishing.h"

namespace phyir::scenes {

namespace {

const char* role_of(const WallOpening& o) {
  if (o.kind == WallOpeningKind::Door) return o.other == -1 ? "entrance_door" : "door";
  return o.bottom < 0.3f ? "french_window" : "window";
}

int turns_facing(glm::vec2 dir) {
  if (dir.y > 0.5f) return 0;
  if (dir.x > 0.5f) return 1;
  if (dir.y < -0.5f) return 2;
  return 3;
}

PlacedAsset fitted(const WallOpening& o, const AssetEntry* entry, const char* role) {
  PlacedAsset p;
  p.entry = entry;
  p.role = role;
  const glm::vec3 size = entry->size_m;
  const float wall_part = entry->opening.wall_thickness_m > 0.0f ? entry->opening.wall_thickness_m : size.z;
  p.scale = glm::vec3(o.width() / size.x, (o.top - o.bottom) / size.y, o.thickness() / wall_part);
  // The wall part's centre in model z (from the box's back side at -size.z / 2), scaled.
  const float wall_centre_z = (-0.5f * size.z + entry->opening.wall_distance_m + 0.5f * wall_part) * p.scale.z;
  const glm::vec2 into_room = -o.outward;
  p.quarter_turns = turns_facing(into_room);
  const glm::vec2 c = o.footprint.centre() - into_room * wall_centre_z;
  p.position = glm::vec3(c.x, o.bottom, c.y);
  return p;
}

}  // namespace

void fit_openings(const ApartmentPlan& plan, const AssetLibrary& library, std::vector<PlacedAsset>& items, Pcg32& rng,
                  std::vector<std::string>& missing) {
  // One model per role for the whole apartment, as a builder would buy them.
  std::map<std::string, const AssetEntry*> chosen;
  for (const WallOpening& o : plan.openings) {
    const char* role = role_of(o);
    auto it = chosen.find(role);
    if (it == chosen.end()) {
      const std::vector<const AssetEntry*> candidates = role_candidates(library, role_spec(role));
      const AssetEntry* e = pick(candidates, rng);
      if (!e && std::string(role) == "french_window") e = pick(role_candidates(library, role_spec("window")), rng);
      it = chosen.emplace(role, e).first;
    }
    // A library without such a model leaves the opening open.
    if (it->second) items.push_back(fitted(o, it->second, role));
    else missing.push_back(role);
  }
}

}  // namespace phyir::scenes
