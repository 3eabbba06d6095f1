#pragma once
// The scene's own environment (extras.phyir.environment), as `phyir render` loads it, for the
// bench commands that build their RenderScene themselves: the day apartments' sky lights the
// rooms through their windows, and a benchmark without it measures another scene.
#include <memory>

#include "phyir/render/environment_light.h"
#include "phyir/scenes/scene.h"

namespace phyir::cli {

// Null when the scene has none. Throws phyir::Error naming the file when it cannot be used.
std::unique_ptr<render::EnvironmentLight> scene_environment(const scenes::Scene& scene);

}  // namespace phyir::cli
