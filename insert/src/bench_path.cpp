// The temporal case of `phyir bench insert`: the object moved along the floor in steps of a few
// pixels, one composite per lighting and one truth per frame (seed 1 throughout, as
// dynamic insertion renders its frames). The object's shading per frame is its mean colour
// over its own pixels (the composite's object mask, the same for the truth); the score is how
// far the composites' frame-to-frame changes are from the truth's (insert_scores.h).
#include <fmt/format.h>

#include <algorithm>
#include <spdlog/spdlog.h>

#include "phyir/insert/insert_bench.h"
#include "phyir/core/error.h"
#include "phyir/core/image_io.h"
#include "phyir/insert/pixel_render.h"

namespace phyir::insert {

namespace fs = std::filesystem;

namespace {

// `steps` pixels of one floor row, `stride` columns apart, each flat at the floor's height and
// clear for the object: the run whose first pixel is nearest `start` (in pixels); empty if none.
std::vector<glm::ivec2> floor_path(const InsertView& v, const scenes::Scene& scene, const BenchPlacement& start,
                                   int steps, int stride, float half_width, float height) {
  const float floor_y = surface_at(v, start.x, start.y).position.y;
  auto usable = [&](int x, int y) {
    if (!(v.depth.at(x, y) > 0.0f) || v.normal.at(x, y, 1) < 0.95f) return false;
    const glm::vec3 p = surface_at(v, x, y).position;
    return std::abs(p.y - floor_y) <= 0.01f && clear_of_scene(scene, p, half_width, height);
  };
  std::vector<std::pair<int, glm::ivec2>> starts;  // by pixel distance from the placement
  for (int y = v.height() / 2; y < v.height(); ++y)
    for (int x = 0; x < v.width(); ++x) {
      const int dx = std::min(std::abs(x - start.x), v.width() - std::abs(x - start.x));
      starts.push_back({dx * dx + (y - start.y) * (y - start.y), {x, y}});
    }
  std::sort(starts.begin(), starts.end(), [](const auto& a, const auto& b) {
    return a.first < b.first || (a.first == b.first && (a.second.y < b.second.y || (a.second.y == b.second.y && a.second.x < b.second.x)));
  });
  for (const auto& [d, s] : starts) {
    std::vector<glm::ivec2> path;
    for (int k = 0; k < steps; ++k) {
      const int x = (s.x + k * stride) % v.width();
      if (!usable(x, s.y)) break;
      path.push_back({x, s.y});
    }
    if (int(path.size()) == steps) return path;
  }
  return {};
}

}  // namespace

PathScores run_path(const InsertView& v, const BenchRoom& room, const BenchPlacement& start,
                    const BenchObject& object, const BenchSettings& o, const fs::path& dir) {
  PathScores r;
  r.object = object.name;
  const scenes::Bounds b = object.scene.compute_bounds();
  const float half_width = 0.5f * std::max(b.max.x - b.min.x, b.max.z - b.min.z), height = b.max.y - b.min.y;
  r.pixels = floor_path(v, room.scene, start, o.path_steps, o.path_stride, half_width, height);
  if (r.pixels.empty())
    fail("{}: no straight floor path of {} steps {} pixels apart, clear for the object", v.dir.string(), o.path_steps,
         o.path_stride);
  std::map<std::string, std::vector<glm::dvec3>> shading;
  std::vector<glm::dvec3> truth_shading;
  InsertRequest request;
  request.spp = o.spp;
  for (size_t k = 0; k < r.pixels.size(); ++k) {
    request.x = r.pixels[k].x, request.y = r.pixels[k].y;
    const fs::path frame = dir / fmt::format("frame_{:03d}", k);
    const scenes::Scene placed = place_object(object.scene, surface_at(v, request.x, request.y), request.placement);
    Image object_mask, region;
    for (const std::string& lighting : o.lightings) {
      request.lighting = bench_lighting(lighting);
      const InsertResult result = insert_object(v, object.scene, request);
      if (object_mask.empty()) object_mask = result.composite.mask, region = result.with_object.mask;
      write_insert_outputs(frame / lighting, v, result);
      shading[lighting].push_back(masked_mean(result.composite.color, object_mask));
    }
    const Image truth = true_render(room, placed, v, o.truth_spp, request.seed, dilated_pixels(region, 0));
    fs::create_directories(frame);
    write_image(frame / "truth.exr", truth);
    truth_shading.push_back(masked_mean(truth, object_mask));
    spdlog::info("bench insert: path {} frame {}/{} at pixel ({}, {})", object.name, k + 1, r.pixels.size(),
                 request.x, request.y);
  }
  r.truth_rms_change = rms_change(truth_shading);
  for (const auto& [lighting, frames] : shading) {
    r.change_error[lighting] = change_error(frames, truth_shading);
    r.rms_change[lighting] = rms_change(frames);
  }
  return r;
}

}  // namespace phyir::insert
