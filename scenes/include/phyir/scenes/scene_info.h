#pragma once
// What `phyir scenes info` reports about a loaded scene: geometry and source counts,
// materials (textures, extensions, emissive / transmissive), emitters with an emitted
// power estimate, cameras, candidate viewpoints, bounds and the loader's warnings.
#include <nlohmann/json.hpp>

#include <string>

#include "phyir/scenes/scene.h"

namespace phyir::scenes {

nlohmann::json scene_info_json(const Scene& scene);

// The same content for people, one topic per line or block.
std::string scene_info_text(const Scene& scene);

}  // namespace phyir::scenes
