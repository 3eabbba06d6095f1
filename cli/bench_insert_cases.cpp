// One case of `phyir bench insert`: an object at a placement, over seeds 1..N. Per seed the
// truth (the scene with the object in it, path traced from the view's camera) and one
// composite per lighting source, scored over the object and its support disc (the with-object
// render's geometry mask): RMSE in linear HDR, SSIM of the display-encoded images.
#include <spdlog/spdlog.h>

#include <chrono>

#include "bench_insert.h"
#include "phyir/core/colour.h"
#include "phyir/core/image_io.h"
#include "phyir/render/render_job.h"
#include "phyir/render/render_view.h"

namespace phyir::cli {

namespace fs = std::filesystem;

namespace {

double seconds_since(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

}  // namespace

insert::LightingRequest bench_lighting(const std::string& label) {
  insert::LightingRequest r;
  r.source = label;
  if (label == "gt_plane") r.source = "gt", r.support_plane_only = true;
  if (label == "gt_projected") r.source = "gt", r.neighbourhood_radius = 0.0f;
  return r;
}

Image true_render(const scenes::Scene& scene, const scenes::Scene& placed, const insert::InsertView& v, int spp,
                  uint64_t seed) {
  const scenes::Scene both = insert::merge_scenes(scene, placed);
  const render::RenderScene rs(both, render::scene_environment(scene));
  render::RenderSettings settings;
  settings.spp = spp;
  settings.seed = seed;
  settings.aovs = false;
  settings.progress = false;
  return render::render_view(rs, insert::panorama_camera(v), settings).film.color();
}

CaseScores run_case(const insert::InsertView& v, const scenes::Scene& scene, const NamedPlacement& p,
                    const BenchObject& object, const BenchInsertOptions& o, const fs::path& dir) {
  CaseScores r{p.name, object.name};
  insert::InsertRequest request;
  request.x = p.x, request.y = p.y;
  request.spp = o.spp;
  const scenes::Scene placed = insert::place_object(object.scene, insert::surface_at(v, p.x, p.y), request.placement);
  const auto display = [&](const Image& linear) {
    return linear_to_display(linear, float(v.exposure_stops), v.display_view);
  };
  for (int seed = 1; seed <= o.seeds; ++seed) {
    request.seed = uint64_t(seed);
    const fs::path seed_dir = dir / fmt::format("seed_{}", seed);
    auto start = std::chrono::steady_clock::now();
    const Image truth = true_render(scene, placed, v, o.truth_spp, request.seed);
    r.truth_seconds.push_back(seconds_since(start));
    fs::create_directories(seed_dir);
    write_image(seed_dir / "truth.exr", truth);
    const Image truth_display = display(truth);
    write_image(seed_dir / "truth.png", truth_display);
    Image region;
    for (const std::string& lighting : o.lightings) {
      request.lighting = bench_lighting(lighting);
      start = std::chrono::steady_clock::now();
      const insert::InsertResult result = insert::insert_object(v, object.scene, request);
      r.composite_seconds.push_back(seconds_since(start));
      if (region.empty()) region = result.with_object.mask;  // the object and its support disc
      insert::write_insert_outputs(seed_dir / lighting, v, result);
      r.rmse[lighting].push_back(insert::masked_rmse(result.composite.color, truth, region));
      r.ssim[lighting].push_back(insert::masked_ssim(display(result.composite.color), truth_display, region));
    }
    spdlog::info("bench insert: {} on the {}, seed {}: truth {:.1f} s", object.name, p.name, seed,
                 r.truth_seconds.back());
  }
  return r;
}

}  // namespace phyir::cli
