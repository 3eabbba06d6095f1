#pragma once
// Placement moves inside one room of an apartment: against a wall, in a corner, in front of
// another piece, around a table, beside a bed, on top of a surface, under the ceiling, in
// the middle. Each tries a few random positions and keeps the first that is free: inside the
// room, clear of the other pieces' boxes (pieces may only overlap where their meshes do
// not cross), of the walkways in front of doors and of the light in front of windows.
#include <vector>

#include "phyir/core/pcg32.h"
#include "phyir/scenes/apartment_furnishing.h"

namespace phyir::scenes {

class RoomPlacer {
 public:
  RoomPlacer(const ApartmentPlan& plan, int room, std::vector<PlacedAsset>& items, AssetModelCache& models,
             Pcg32& rng);

  // Each returns the new piece's index in `items`, or -1 when no free position was found.
  // Back against wall `wall` (0: the -z wall, 1: +x, 2: +z, 3: -x; -1: any), front into the room.
  int against_wall(const AssetEntry* entry, const std::string& role, int wall = -1);
  // Against a wall, at one end of it (plants, floor lamps, wardrobes).
  int in_corner(const AssetEntry* entry, const std::string& role);
  // Facing `other` across `gap` metres, centred on it (a coffee table before a sofa).
  int in_front_of(int other, const AssetEntry* entry, const std::string& role, float gap);
  // On both sides of `bed`, backs against the same wall; returns how many were placed.
  int beside(int bed, const AssetEntry* entry, const std::string& role);
  // Around `table`, facing it, tucked in as far as their meshes allow; returns the count.
  int around(int table, const AssetEntry* entry, const std::string& role, int most);
  // On the top surface of `host` (its drop-on-top elevation), inside its outline.
  int on_top(int host, const AssetEntry* entry, const std::string& role);
  // Hanging from the ceiling near the room's centre.
  int on_ceiling(const AssetEntry* entry, const std::string& role);
  // Standing near the room's centre, turned along its longer side.
  int in_middle(const AssetEntry* entry, const std::string& role);

  int wall_of(int piece) const;  // the wall a piece's back is against, or -1
  int piece_count() const { return static_cast<int>(items_.size()); }
  const Rect2& floor() const { return floor_; }

 private:
  int try_add(PlacedAsset piece, int may_overlap = -1);
  // Back against wall w at `along` on it, front into the room; records the wall.
  int try_on_wall(const AssetEntry* entry, const std::string& role, int w, float along);
  glm::vec2 wall_extent(int w) const;
  bool is_free(const PlacedAsset& piece, int may_overlap) const;
  PlacedAsset make(const AssetEntry* entry, const std::string& role) const;
  void add_keepouts();

  const ApartmentPlan& plan_;
  int room_;
  Rect2 floor_;
  std::vector<PlacedAsset>& items_;
  AssetModelCache& models_;
  Pcg32& rng_;
  std::vector<Box3> keepouts_;  // door walkways (full height) and window light (from the sill)
  std::vector<int> wall_of_;    // per item index, -1 if not against a wall
};

}  // namespace phyir::scenes
