// One case of `phyir bench insert`: an object at a placement, over seeds 1..N. Per seed the
// truth (the scene with the object in it, path traced from the view's camera) and one
// composite per lighting source, scored over the object and its support disc (the with-object
// render's geometry mask): RMSE in linear HDR, SSIM of the display-encoded images.
#include <spdlog/spdlog.h>

#include "phyir/insert/insert_bench.h"
#include "phyir/core/stopwatch.h"
#include "phyir/core/colour.h"
#include "phyir/core/image_io.h"
#include "phyir/render/render_view.h"
#include "phyir/insert/pixel_render.h"

namespace phyir::insert {

namespace fs = std::filesystem;

LightingRequest bench_lighting(const std::string& label) {
  LightingRequest r;
  r.source = label;
  if (label == "gt_plane") r.source = "gt", r.support_plane_only = true;
  if (label == "gt_projected") r.source = "gt", r.neighbourhood_radius = 0.0f;
  if (label == "gt_p4") r.source = "gt", r.blend_power = 4.0f;
  if (label == "gt_foot") r.source = "gt", r.blend_distance = BlendDistance::kFoot;
  if (label == "gt_point") r.source = "gt", r.blend_distance = BlendDistance::kPoint;
  return r;
}

Image true_render(const BenchRoom& room, const scenes::Scene& placed, const InsertView& v, int spp,
                  uint64_t seed, const std::vector<glm::ivec2>& pixels) {
  const scenes::Scene both = merge_scenes(room.scene, placed);
  const render::RenderScene rs(
      both, room.environment ? std::make_unique<render::EnvironmentLight>(*room.environment) : nullptr);
  render::RenderSettings settings;
  settings.spp = spp;
  settings.seed = seed;
    Image color = v.color;
  render_pixels(rs, panorama_camera(v), settings, pixels, color);
  return color;
}

CaseScores run_case(const InsertView& v, const BenchRoom& room, const BenchPlacement& p,
                    const BenchObject& object, const BenchSettings& o, const fs::path& dir) {
  CaseScores r;
  r.placement = p.name;
  r.object = object.name;
  InsertRequest request;
  request.x = p.x, request.y = p.y;
  request.spp = o.spp;
  const scenes::Scene placed = place_object(object.scene, surface_at(v, p.x, p.y), request.placement);
  const auto display = [&](const Image& linear) {
    return linear_to_display(linear, float(v.exposure_stops), v.display_view);
  };
  for (int seed = 1; seed <= o.seeds; ++seed) {
    request.seed = uint64_t(seed);
    const fs::path seed_dir = dir / fmt::format("seed_{}", seed);
    std::map<std::string, Image> composites;
    Image region;
    for (const std::string& lighting : o.lightings) {
      request.lighting = bench_lighting(lighting);
      request.lighting.predicted_dir = o.predicted_dir;
      const Stopwatch composite_watch;
      const InsertResult result = insert_object(v, object.scene, request);
      r.composite_seconds.push_back(composite_watch.seconds());
      if (region.empty()) region = result.with_object.mask;  // the object and its support disc
      write_insert_outputs(seed_dir / lighting, v, result);
      composites[lighting] = result.composite.color;
    }
    const Stopwatch truth_watch;
    const Image truth =
        true_render(room, placed, v, o.truth_spp, request.seed, dilated_pixels(region, kTruthMarginPixels));
    r.truth_seconds.push_back(truth_watch.seconds());
    fs::create_directories(seed_dir);
    write_image(seed_dir / "truth.exr", truth);
    const Image truth_display = display(truth);
    write_image(seed_dir / "truth.png", truth_display);
    for (const std::string& lighting : o.lightings) {
      r.rmse[lighting].push_back(masked_rmse(composites[lighting], truth, region));
      r.ssim[lighting].push_back(masked_ssim(display(composites[lighting]), truth_display, region));
    }
    spdlog::info("bench insert: {} on the {}, seed {}: truth {:.1f} s", object.name, p.name, seed,
                 r.truth_seconds.back());
  }
  return r;
}

}  // namespace phyir::insert
