#include "punctual_deposit.h"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <atomic>
#include <cmath>

#include "phyir/core/safe_math.h"
#include "phyir/render/equirect.h"

namespace phyir::render {

glm::ivec2 probe_texel_of(const glm::vec3& d, int height, int width) {
  const glm::vec2 uv = equirect_uv(d);
  const int row = std::clamp(int(std::floor(uv.y * float(height))), 0, height - 1);
  const int col = std::clamp(int(std::floor(uv.x * float(width))), 0, width - 1);
  return {row, col};
}

namespace {

// Whether nothing hides the light `seen` describes from `origin` (one shadow ray, counted).
bool unoccluded(const RenderScene& scene, const glm::vec3& origin, const DeltaIllumination& seen, uint64_t* rays) {
  Ray shadow{origin, seen.wi};
  if (std::isfinite(seen.distance)) shadow.tmax = seen.distance * (1.0f - kShadowRayShortening);
  ++*rays;
  return !scene.accelerator().occluded(shadow);
}

// The light `light` sends to `origin` if nothing hides it, as a texel and the radiance to add.
bool punctual_texel(const RenderScene& scene, int light, const glm::vec3& origin, const ProbeLayout& layout,
                    glm::ivec2* texel, glm::vec3* radiance, uint64_t* rays) {
  DeltaIllumination seen;
  if (!scene.emitters().delta_lights().illuminate(light, origin, &seen)) return false;
  if (!unoccluded(scene, origin, seen, rays)) return false;
  *texel = probe_texel_of(seen.wi, layout.res_height, layout.res_width);
  *radiance = seen.irradiance / equirect_texel_solid_angle(texel->x, layout.res_width, layout.res_height);
  return is_finite(*radiance);
}

}  // namespace

uint64_t deposit_punctual_lights(const RenderScene& scene, const ProbeLayout& layout,
                                 const std::vector<ProbeSite>& sites, const std::vector<int>& probes, Image* mosaic) {
  const DeltaLights& lights = scene.emitters().delta_lights();
  if (lights.empty()) return 0;
  std::atomic<uint64_t> rays{0};
  tbb::parallel_for(size_t(0), probes.size(), [&](size_t k) {
    const int p = probes[k];
    uint64_t traced = 0;
    for (int light = 0; light < lights.size(); ++light) {
      glm::ivec2 texel;
      glm::vec3 radiance;
      if (!punctual_texel(scene, light, sites[size_t(p)].origin, layout, &texel, &radiance, &traced)) continue;
      const glm::ivec2 at = layout.mosaic_pixel(p, texel.x * layout.res_width + texel.y);
      for (int c = 0; c < 3; ++c) mosaic->at(at.x, at.y, c) += radiance[c];
    }
    rays.fetch_add(traced, std::memory_order_relaxed);
  });
  return rays.load();
}

}  // namespace phyir::render
