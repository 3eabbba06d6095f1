#pragma once
// Furniture for an apartment plan: pieces of a Sweet Home 3D library (asset_library.h)
// placed by room type with rules a person would recognise (a sofa against a wall facing the
// room, a coffee table in front of it, chairs around a dining table, a bed with bedside
// tables, kitchen units along a wall, small objects on tables and shelves), doors and
// windows in the plan's openings, and lamps. docs/apartments.md states every rule.
#include <glm/glm.hpp>

#include <cstdint>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "phyir/scenes/apartment_plan.h"
#include "phyir/scenes/asset_library.h"
#include "phyir/scenes/room_layout.h"

namespace phyir::scenes {

// One placed piece. Its model (normalised: bottom centre at the origin, front +Z) is scaled
// by `scale`, turned by `yaw` about +Y, and moved to `position`.
struct PlacedAsset {
  const AssetEntry* entry = nullptr;
  std::string role;  // "sofa", "dining_chair", "door", "window", ...
  int room = -1;     // plan room, or -1 for doors and windows between rooms or to outside
  glm::vec3 position{0.0f};  // world position of the model's bottom centre
  int quarter_turns = 0;     // yaw = quarter_turns x 90 degrees: front +Z turns to +X at 1
  glm::vec3 scale{1.0f};     // per model axis; 1 except for doors and windows
  int host = -1;             // index of the piece it stands on, -1 for none
  bool lamp_on = false;      // a lamp whose light sources are lit

  glm::vec3 size() const;        // the scaled catalog size, in model axes
  Box3 bounds() const;           // world box of the size box
  glm::mat4 model_to_world() const;
  glm::vec3 front() const;       // world direction of the model's +Z
};

// Loaded models, shared by placement checks and the writer (a model is read once).
class AssetModelCache {
 public:
  const AssetModel& get(const AssetEntry& entry);

 private:
  std::map<std::string, std::unique_ptr<AssetModel>> models_;  // by "archive|id"
};

enum class ApartmentLighting { Day, Night };
const char* apartment_lighting_name(ApartmentLighting lighting);

struct ApartmentFurnishing {
  std::vector<PlacedAsset> items;
  std::vector<std::string> unfurnished_roles;  // roles no library entry matched, once per attempt
};

// Places furniture, doors, windows and lamps; lamps are lit at night. A role the library has
// no model for is skipped (an opening without a door or window model stays open) and listed
// in unfurnished_roles.
ApartmentFurnishing furnish_apartment(const ApartmentPlan& plan, const AssetLibrary& library,
                                      AssetModelCache& models, ApartmentLighting lighting);

// True when the two placed pieces' triangles cross (Embree: every triangle edge of each is
// traced against the other's triangles). Pieces whose boxes are apart never cross.
bool pieces_interpenetrate(const PlacedAsset& a, const PlacedAsset& b, AssetModelCache& models);

}  // namespace phyir::scenes
