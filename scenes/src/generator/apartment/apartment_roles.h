#pragma once
// What each furniture role is, as a test on library entries: categories, words in the
// name (and words that rule an entry out), and a plausible size. The words are English
// catalog names (Sweet Home 3D's default language); another library in the same format
// matches as far as its names use the same words.
#include <string>
#include <vector>

#include "phyir/core/pcg32.h"
#include "phyir/scenes/asset_library.h"

namespace phyir::scenes {

struct RoleSpec {
  std::string role;
  std::vector<std::string> categories;  // any of; empty = every category
  std::vector<std::string> words;       // the lower-case name contains one of these
  std::vector<std::string> not_words;   // and none of these
  glm::vec3 min_size{0.0f};             // metres, catalog width, height, depth
  glm::vec3 max_size{100.0f};
  bool light = false;                   // only lamps (entries with light sources)
};

// The spec of a role by name; throws phyir::Error for an unknown role.
const RoleSpec& role_spec(const std::string& role);

// Library entries that fit the role, in library order.
std::vector<const AssetEntry*> role_candidates(const AssetLibrary& library, const RoleSpec& spec);

// One candidate, drawn by `rng`, or nullptr when there is none.
const AssetEntry* pick(const std::vector<const AssetEntry*>& candidates, Pcg32& rng);

}  // namespace phyir::scenes
