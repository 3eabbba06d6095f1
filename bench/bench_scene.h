#pragma once
// The scene the micro-benchmarks run on: a generated `hard` room, loaded like any glTF.
#include "phyir/render/render_scene.h"
#include "phyir/scenes/scene.h"

namespace phyir::bench {

struct BenchScene {
  scenes::Scene scene;
  std::unique_ptr<render::RenderScene> render_scene;
  glm::vec3 viewpoint{0.0f};
};

// Generated once per process (room 0 of seed 1) into the system temp folder.
const BenchScene& bench_scene();

}  // namespace phyir::bench
