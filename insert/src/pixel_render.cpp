#include "phyir/insert/pixel_render.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include "phyir/core/error.h"
#include "phyir/render/effects.h"
#include "phyir/render/path_tracer.h"

namespace phyir::insert {

std::vector<glm::ivec2> dilated_pixels(const Image& mask, int margin) {
  const int w = mask.width, h = mask.height;
  std::vector<char> keep(size_t(w) * h, 0);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      if (mask.at(x, y, 0) < 0.5f) continue;
      for (int dy = -margin; dy <= margin; ++dy)
        for (int dx = -margin; dx <= margin; ++dx) {
          const int py = y + dy, px = ((x + dx) % w + w) % w;
          if (py >= 0 && py < h) keep[size_t(py) * w + px] = 1;
        }
    }
  std::vector<glm::ivec2> out;
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x)
      if (keep[size_t(y) * w + x]) out.push_back({x, y});
  return out;
}

void render_pixels(const render::RenderScene& scene, const render::CameraModel& camera,
                   const render::RenderSettings& settings, const std::vector<glm::ivec2>& pixels, Image& color) {
  if (settings.guiding.enabled) fail("rendering selected pixels: path guiding is not supported");
  if (color.width != camera.width || color.height != camera.height || color.channels < 3)
    fail("rendering selected pixels: a {}x{}x{} image for a {}x{} camera", color.width, color.height, color.channels,
         camera.width, camera.height);
  // The same effects and path tracer as render_view builds for this scene.
  const render::Effects effects = settings.force_all_effects
                                      ? render::all_effects()
                                      : render::analyse_effects(scene.scene(), scene.environment() != nullptr);
  const render::PathTracer tracer(scene, effects, settings.path);
  tbb::parallel_for(tbb::blocked_range<size_t>(0, pixels.size(), 16), [&](const tbb::blocked_range<size_t>& r) {
    render::PathCounters counters;
    for (size_t k = r.begin(); k < r.end(); ++k) {
      const glm::ivec2 p = pixels[k];
      const glm::dvec3 sum =
          render::sum_pixel_samples(tracer, camera, settings.seed, p.x, p.y, camera.width, 0, settings.spp, &counters);
      const glm::vec3 v(sum / double(settings.spp));
      for (int c = 0; c < 3; ++c) color.at(p.x, p.y, c) = v[c];
    }
  });
}

}  // namespace phyir::insert
