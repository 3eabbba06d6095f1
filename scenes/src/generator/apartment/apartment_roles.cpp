// The furniture roles of docs/apartments.md, "Furniture rules".
#include "generator/apartment/apartment_roles.h"

#include <algorithm>
#include <cctype>

#include "phyir/core/error.h"

namespace phyir::scenes {

namespace {

const std::vector<RoleSpec>& all_roles() {
  static const glm::vec3 any_max(100.0f);
  static const std::vector<RoleSpec> roles = {
      {"sofa", {"Living room"}, {"sofa", "couch"}, {"convertible", "corner", "opened"}, {1.3f, 0.5f, 0.6f}, {3.0f, 1.2f, 1.3f}},
      {"armchair", {"Living room", "Office"}, {"armchair"}, {"ottoman"}, {0.5f, 0.5f, 0.5f}, {1.2f, 1.3f, 1.2f}},
      {"coffee_table", {"Living room"}, {"coffee table"}, {}, {0.4f, 0.2f, 0.4f}, {1.6f, 0.6f, 1.2f}},
      {"tv_stand", {"Living room"}, {"tv stand", "television cabinet"}, {}, {0.6f, 0.3f, 0.3f}, {2.5f, 1.6f, 0.8f}},
      {"bookcase", {"Living room", "Office", "Bedroom"}, {"bookcase", "shelves"}, {"upper"}, {0.4f, 0.8f, 0.2f}, {2.4f, 2.4f, 0.7f}},
      {"plant", {"Living room", "Miscellaneous"}, {"plant", "ficus", "yucca", "bamboo", "spathiphyllum", "tree"},
       {"christmas", "little", "succulent", "bonsai"}, {0.2f, 0.5f, 0.2f}, {1.5f, 2.2f, 1.5f}},
      {"rug", {"Living room", "Miscellaneous"}, {"rug", "carpet"}, {}, {1.0f, 0.0f, 0.8f}, {3.5f, 0.05f, 3.0f}},
      {"dining_table", {"Living room", "Kitchen", "Office"}, {"table"},
       {"coffee", "bedside", "child", "folding", "trestle", "dressing", "changing", "technical", "bar", "desk", "island",
        "children"},
       {0.7f, 0.65f, 0.7f}, {2.2f, 0.85f, 1.3f}},
      {"dining_chair", {"Living room", "Kitchen"}, {"chair"},
       {"arm", "child", "baby", "high", "bar", "rocking", "folding", "class"}, {0.35f, 0.7f, 0.35f}, {0.7f, 1.15f, 0.7f}},
      {"floor_lamp", {"Lights"}, {"lamp"},
       {"desk", "little", "camping", "street", "park", "porch", "outdoor", "ceiling", "wall", "pendant", "hanging",
        "chandelier", "lamppost"},
       {0.1f, 1.0f, 0.1f}, {1.0f, 2.2f, 1.0f}, true},
      {"table_lamp", {"Lights"}, {"lamp"}, {"camping", "street", "park", "porch", "outdoor", "ceiling", "wall", "lamppost"},
       {0.05f, 0.15f, 0.05f}, {0.6f, 0.8f, 0.6f}, true},
      {"ceiling_light", {"Lights"}, {"ceiling lamp", "chandelier", "pendant", "hanging light", "fluorescent light"}, {},
       {0.1f, 0.02f, 0.1f}, {1.6f, 1.2f, 1.6f}, true},
      {"fridge", {"Kitchen"}, {"fridge", "refrigerator"}, {"large"}, {0.5f, 1.2f, 0.5f}, {1.0f, 2.1f, 0.9f}},
      {"stove", {"Kitchen"}, {"cooker", "stove", "oven"}, {"small", "double", "microwave", "toaster", "induction"},
       {0.5f, 0.5f, 0.45f}, {1.1f, 1.0f, 0.8f}},
      {"sink_unit", {"Kitchen"}, {"sink"}, {}, {0.4f, 0.7f, 0.4f}, {1.6f, 1.3f, 0.8f}},
      {"lower_cabinet", {"Kitchen"}, {"lower cabinet", "drawers cabinet"}, {"corner"}, {0.3f, 0.7f, 0.4f}, {1.2f, 1.0f, 0.8f}},
      {"upper_cabinet", {"Kitchen"}, {"upper cabinet", "upper shelves cabinet"}, {"corner"}, {0.3f, 0.3f, 0.2f}, {1.2f, 1.0f, 0.5f}},
      {"kitchen_small", {"Kitchen"},
       {"toaster", "coffee maker", "coffee machine", "microwave", "kettle", "blender", "bowl with fruits", "bread box",
        "teapot", "mixer", "coffee brewer", "utensils pot", "induction cooker"},
       {}, {0.05f, 0.05f, 0.05f}, {0.6f, 0.5f, 0.5f}},
      {"bed", {"Bedroom"}, {"bed"},
       {"bunk", "baby", "child", "captain", "hospital", "mezzanine", "air", "crib", "sofa", "changing", "day bed", "bedside"},
       {0.8f, 0.3f, 1.8f}, {2.2f, 1.6f, 2.4f}},
      {"bedside_table", {"Bedroom"}, {"bedside table"}, {}, {0.3f, 0.3f, 0.25f}, {0.8f, 0.8f, 0.7f}},
      {"wardrobe", {"Bedroom"}, {"wardrobe", "cupboard", "chest", "dresser"}, {"dressing"}, {0.5f, 0.5f, 0.35f}, {2.5f, 2.4f, 0.8f}},
      {"bath", {"Bathroom"}, {"bath", "shower stall"}, {"bathmat", "island"}, {0.7f, 0.4f, 0.7f}, {2.0f, 2.3f, 1.6f}},
      {"toilet", {"Bathroom"}, {"toilet"}, {"brush", "paper"}, {0.3f, 0.5f, 0.4f}, {0.7f, 1.3f, 0.9f}},
      {"washbasin", {"Bathroom"}, {"washbasin", "vanity", "basin", "lavatory"}, {}, {0.35f, 0.6f, 0.25f}, {1.8f, 2.2f, 0.8f}},
      {"towel_rack", {"Bathroom"}, {"towel rack", "radiator"}, {}, {0.3f, 0.4f, 0.05f}, {1.2f, 1.9f, 0.5f}},
      {"bathroom_small", {"Bathroom"}, {"soap", "bottle", "cosmetics", "flacon", "sponge", "comb", "brush"}, {"toilet"},
       {0.01f, 0.01f, 0.01f}, {0.3f, 0.3f, 0.3f}},
      {"decor", {"Living room", "Miscellaneous", "Bedroom", "Office"},
       {"vase", "flowers", "tulips", "orchids", "lily", "little plant", "succulent", "clock", "bowl", "candle", "book",
        "statue", "sculpture", "globe", "chessboard", "teddy"},
       {"bookcase", "shelves"}, {0.03f, 0.03f, 0.03f}, {0.5f, 0.6f, 0.5f}},
      {"desk", {"Office"}, {"desk"}, {"lamp"}, {0.8f, 0.65f, 0.5f}, {1.8f, 0.9f, 1.0f}},
      {"desk_chair", {"Office"}, {"chair"}, {"arm", "class"}, {0.4f, 0.7f, 0.4f}, {0.8f, 1.3f, 0.8f}},
      {"door", {"Doors and windows"}, {"door"}, {"garage", "elevator", "exterior", "screen", "glass", "double"},
       {0.6f, 1.8f, 0.0f}, {1.1f, 2.3f, any_max.z}},
      {"entrance_door", {"Doors and windows"}, {"exterior door", "door"}, {"garage", "elevator", "screen", "double", "glass"},
       {0.7f, 1.8f, 0.0f}, {1.2f, 2.4f, any_max.z}},
      {"window", {"Doors and windows"}, {"window"}, {"shutter", "french"}, {0.4f, 0.4f, 0.0f}, {3.0f, 2.4f, any_max.z}},
      {"french_window", {"Doors and windows"}, {"french window"}, {}, {0.4f, 1.8f, 0.0f}, {3.5f, 2.6f, any_max.z}},
  };
  return roles;
}

std::string lower(std::string s) {
  std::transform(s.begin(), s.end(), s.begin(), [](unsigned char c) { return char(std::tolower(c)); });
  return s;
}

bool fits(const AssetEntry& e, const RoleSpec& spec) {
  if (!spec.categories.empty() &&
      std::find(spec.categories.begin(), spec.categories.end(), e.category) == spec.categories.end())
    return false;
  const std::string name = lower(e.name);
  auto has = [&](const std::string& w) { return name.find(w) != std::string::npos; };
  if (std::none_of(spec.words.begin(), spec.words.end(), has)) return false;
  if (std::any_of(spec.not_words.begin(), spec.not_words.end(), has)) return false;
  if (spec.light != e.is_light() && (spec.light || e.category == "Lights")) return false;
  for (int a = 0; a < 3; ++a)
    if (e.size_m[a] < spec.min_size[a] || e.size_m[a] > spec.max_size[a]) return false;
  return true;
}

}  // namespace

const RoleSpec& role_spec(const std::string& role) {
  for (const RoleSpec& s : all_roles())
    if (s.role == role) return s;
  fail("apartment: no furniture role '{}'", role);
}

std::vector<const AssetEntry*> role_candidates(const AssetLibrary& library, const RoleSpec& spec) {
  std::vector<const AssetEntry*> out;
  for (const AssetEntry& e : library.entries())
    if (fits(e, spec) && (spec.categories != std::vector<std::string>{"Doors and windows"} || e.is_door_or_window))
      out.push_back(&e);
  return out;
}

const AssetEntry* pick(const std::vector<const AssetEntry*>& candidates, Pcg32& rng) {
  if (candidates.empty()) return nullptr;
  return candidates[rng.below(static_cast<uint32_t>(candidates.size()))];
}

}  // namespace phyir::scenes
