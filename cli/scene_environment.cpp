// The scene's own environment for the bench commands (scene_environment.h).
#include "scene_environment.h"

#include "phyir/core/error.h"
#include "phyir/core/image_io.h"

namespace phyir::cli {

std::unique_ptr<render::EnvironmentLight> scene_environment(const scenes::Scene& scene) {
  if (!scene.environment) return nullptr;
  const Image image = read_image(scene.environment->path);
  if (image.channels < 3)
    fail("{}: environment map needs RGB, found {} channel(s)", scene.environment->path.string(), image.channels);
  return std::make_unique<render::EnvironmentLight>(image, scene.environment->scale);
}

}  // namespace phyir::cli
