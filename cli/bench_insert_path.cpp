// The temporal case of `phyir bench insert`: the object moved along the floor in steps of a few
// pixels, one composite per lighting and one truth per frame (seed 1 throughout, as
// `phyir insert --path` renders its frames). The object's shading per frame is its mean colour
// over its own pixels (the composite's object mask, the same for the truth); the score is how
// far the composites' frame-to-frame changes are from the truth's (insert_scores.h).
#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include "bench_insert.h"
#include "phyir/core/error.h"
#include "phyir/core/image_io.h"

namespace phyir::cli {

namespace fs = std::filesystem;

namespace {

// `steps` floor pixels from `start`, `stride` columns apart (to the right, else to the left),
// each flat at the start's height and clear for the object; empty when neither way is.
std::vector<glm::ivec2> floor_path(const insert::InsertView& v, const scenes::Scene& scene, const NamedPlacement& start,
                                   int steps, int stride, float half_width, float height) {
  const float y0 = insert::surface_at(v, start.x, start.y).position.y;
  for (int direction : {1, -1}) {
    std::vector<glm::ivec2> path;
    for (int k = 0; k < steps; ++k) {
      const int x = ((start.x + direction * k * stride) % v.width() + v.width()) % v.width();
      if (!(v.depth.at(x, start.y) > 0.0f) || v.normal.at(x, start.y, 1) < 0.95f) break;
      const glm::vec3 p = insert::surface_at(v, x, start.y).position;
      if (std::abs(p.y - y0) > 0.01f || !clear_of_scene(scene, p, half_width, height)) break;
      path.push_back({x, start.y});
    }
    if (int(path.size()) == steps) return path;
  }
  return {};
}

}  // namespace

PathScores run_path(const insert::InsertView& v, const scenes::Scene& scene, const NamedPlacement& start,
                    const BenchObject& object, const BenchInsertOptions& o, const fs::path& dir) {
  PathScores r;
  r.object = object.name;
  const scenes::Bounds b = object.scene.compute_bounds();
  const float half_width = 0.5f * std::max(b.max.x - b.min.x, b.max.z - b.min.z), height = b.max.y - b.min.y;
  r.pixels = floor_path(v, scene, start, o.path_steps, o.path_stride, half_width, height);
  if (r.pixels.empty())
    fail("{}: no straight floor path of {} steps {} pixels apart from pixel ({}, {})", v.dir.string(), o.path_steps,
         o.path_stride, start.x, start.y);
  std::map<std::string, std::vector<glm::dvec3>> shading;
  std::vector<glm::dvec3> truth_shading;
  insert::InsertRequest request;
  request.spp = o.spp;
  for (size_t k = 0; k < r.pixels.size(); ++k) {
    request.x = r.pixels[k].x, request.y = r.pixels[k].y;
    const fs::path frame = dir / fmt::format("frame_{:03d}", k);
    const scenes::Scene placed = insert::place_object(object.scene, insert::surface_at(v, request.x, request.y), request.placement);
    const Image truth = true_render(scene, placed, v, o.truth_spp, request.seed);
    fs::create_directories(frame);
    write_image(frame / "truth.exr", truth);
    Image object_mask;
    for (const std::string& lighting : o.lightings) {
      request.lighting = bench_lighting(lighting);
      const insert::InsertResult result = insert::insert_object(v, object.scene, request);
      if (object_mask.empty()) object_mask = result.composite.mask;
      insert::write_insert_outputs(frame / lighting, v, result);
      shading[lighting].push_back(insert::masked_mean(result.composite.color, object_mask));
    }
    truth_shading.push_back(insert::masked_mean(truth, object_mask));
    spdlog::info("bench insert: path {} frame {}/{} at pixel ({}, {})", object.name, k + 1, r.pixels.size(),
                 request.x, request.y);
  }
  r.truth_rms_change = insert::rms_change(truth_shading);
  for (const auto& [lighting, frames] : shading) {
    r.change_error[lighting] = insert::change_error(frames, truth_shading);
    r.rms_change[lighting] = insert::rms_change(frames);
  }
  return r;
}

}  // namespace phyir::cli
