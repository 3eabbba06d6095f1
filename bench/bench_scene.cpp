#include "bench_scene.h"

#include <filesystem>

#include "phyir/scenes/gltf_loader.h"
#include "phyir/scenes/room_generator.h"

namespace phyir::bench {

const BenchScene& bench_scene() {
  static const BenchScene* scene = [] {
    const auto dir = std::filesystem::temp_directory_path() / "phyir_microbench_room";
    const scenes::RoomSummary summary = scenes::generate_room(dir, 0, 1, scenes::RoomPreset::Hard);
    auto* s = new BenchScene;
    s->scene = scenes::load_gltf(dir / summary.file);
    s->render_scene = std::make_unique<render::RenderScene>(s->scene);
    s->viewpoint = s->scene.cameras.empty() ? glm::vec3(0, 1.5f, 0) : s->scene.cameras[0].position;
    return s;
  }();
  return *scene;
}

}  // namespace phyir::bench
