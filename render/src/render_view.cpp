#include "phyir/render/render_view.h"

#include <tbb/blocked_range2d.h>
#include <tbb/enumerable_thread_specific.h>
#include <tbb/parallel_for.h>

#include "phyir/core/progress.h"
#include "phyir/core/stopwatch.h"
#include "phyir/render/gbuffer.h"
#include "phyir/render/pixel_sampler.h"
#include "phyir/render/streams.h"

namespace phyir::render {

namespace {

constexpr int kTileSize = 16;

size_t tile_count(int width, int height) {
  return size_t((width + kTileSize - 1) / kTileSize) * size_t((height + kTileSize - 1) / kTileSize);
}

void render_color(const RenderScene& scene, const CameraModel& camera, const RenderSettings& settings,
                  const PathTracer& tracer, Film* film, PathCounters* counters) {
  tbb::enumerable_thread_specific<PathCounters> local;
  Progress progress("render", tile_count(film->width(), film->height()), "tiles", settings.progress);
  tbb::parallel_for(
      tbb::blocked_range2d<int>(0, film->height(), kTileSize, 0, film->width(), kTileSize),
      [&](const tbb::blocked_range2d<int>& tile) {
        PathCounters& c = local.local();
        for (int y = tile.rows().begin(); y < tile.rows().end(); ++y) {
          for (int x = tile.cols().begin(); x < tile.cols().end(); ++x) {
            const glm::dvec3 sum =
                sum_pixel_samples(tracer, camera, settings.seed, x, y, film->width(), 0, settings.spp, &c);
            film->set_color(x, y, glm::vec3(sum / double(settings.spp)));
          }
        }
        progress.advance();
      },
      tbb::simple_partitioner());
  for (const PathCounters& c : local) *counters += c;
}

uint64_t render_gbuffer(const RenderScene& scene, const CameraModel& camera, Film* film) {
  tbb::parallel_for(tbb::blocked_range<int>(0, film->height()), [&](const tbb::blocked_range<int>& rows) {
    for (int y = rows.begin(); y < rows.end(); ++y) {
      for (int x = 0; x < film->width(); ++x) {
        const Ray ray = camera.generate_ray(glm::vec2(x + 0.5f, y + 0.5f));
        SurfaceInteraction si;
        // The AOVs record the first surface, blended or not, and mark a blended one in
        // mask_transparent (docs/conventions.md): a pixel's labels do not flicker with alpha.
        film->set_gbuffer(x, y, scene.trace(ray, &si, Coverage::kBlendSolid) ? GBufferSample::from_hit(si) : GBufferSample{});
      }
    }
  });
  return uint64_t(film->width()) * film->height();
}

}  // namespace

glm::dvec3 sum_pixel_samples(const PathTracer& tracer, const CameraModel& camera, uint64_t seed, int x, int y,
                             int width, int first_sample, int count, PathCounters* counters,
                             guiding::RecordBuffer* records) {
  const uint64_t pixel = uint64_t(y) * width + x;
  // The pixel's scrambling key: from the seed and the pixel, apart from the paths' keys.
  const uint64_t pixel_key = stream_key(sample_key(seed, pixel, 0), Purpose::kPixelScramble);
  glm::dvec3 sum(0.0);
  for (int s = first_sample; s < first_sample + count; ++s) {
    const uint64_t key = sample_key(seed, pixel, s);
    const uint32_t index = uint32_t(s);
    const glm::vec2 p = glm::vec2(x, y) + pixel_sample(index, pixel_key);
    FirstBounceSamples first;
    first.light_select = stratified_1d(index, stream_key(pixel_key, Purpose::kPixelLightSelect));
    first.light_point = pixel_sample(index, stream_key(pixel_key, Purpose::kPixelLightPoint));
    first.lobe = stratified_1d(index, stream_key(pixel_key, Purpose::kPixelLobe));
    first.brdf = pixel_sample(index, stream_key(pixel_key, Purpose::kPixelBrdf));
    sum += glm::dvec3(tracer.radiance(camera.generate_ray(p), key, first, counters, records));
  }
  return sum;
}

nlohmann::json RenderStats::to_json() const {
  return {{"color_seconds", color_seconds},
          {"aov_seconds", aov_seconds},
          {"rays_traced", counters.rays + aov_rays},
          {"path_rays", counters.rays},
          {"aov_rays", aov_rays},
          {"paths", counters.paths},
          {"rays_per_second", color_seconds > 0 ? counters.rays / color_seconds : 0.0},
          {"nonfinite_samples_caught", counters.nonfinite_samples}};
}

RenderOutput render_view(const RenderScene& scene, const CameraModel& camera, const RenderSettings& settings) {
  RenderOutput out{Film(camera.width, camera.height, settings.aovs),
                   settings.force_all_effects ? all_effects()
                                              : analyse_effects(scene.scene(), scene.environment() != nullptr),
                   {}};
  const PathTracer tracer(scene, out.effects, settings.path);
  const Stopwatch color_watch;
  if (settings.guiding.enabled)
    out.stats.guiding = render_color_guided(scene, camera, settings, out.effects, &out.film, &out.stats.counters);
  else
    render_color(scene, camera, settings, tracer, &out.film, &out.stats.counters);
  out.stats.color_seconds = color_watch.seconds();
  if (settings.aovs) {
    const Stopwatch aov_watch;
    out.stats.aov_rays = render_gbuffer(scene, camera, &out.film);
    out.stats.aov_seconds = aov_watch.seconds();
  }
  return out;
}

}  // namespace phyir::render
