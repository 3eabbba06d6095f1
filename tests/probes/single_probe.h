#pragma once
// One probe rendered alone, for the probe tests: its settings, its site, its image.
#include <gtest/gtest.h>

#include <vector>

#include "phyir/core/image.h"
#include "phyir/render/effects.h"
#include "phyir/render/probe_renderer.h"

namespace phyir::render {

// A 1x1 grid of h x w texels, a fixed seed, no progress display.
inline ProbeSettings settings_for(ProbeMode mode, int spp, int h, int w, int max_bounces = 8) {
  ProbeSettings s;
  s.mode = mode;
  s.spp = spp;
  s.layout.grid_height = 1;
  s.layout.grid_width = 1;
  s.layout.res_height = h;
  s.layout.res_width = w;
  s.path.max_bounces = max_bounces;
  s.seed = 5;
  s.progress = false;
  s.cache.samples_per_cell = 64;
  return s;
}

// One probe at `origin`, as if on a surface with normal +Y just below it.
inline std::vector<ProbeSite> single_site(const glm::vec3& origin) {
  ProbeSite s;
  s.surface = origin - glm::vec3(0.0f, 0.01f, 0.0f);
  s.normal = glm::vec3(0.0f, 1.0f, 0.0f);
  s.origin = origin;
  s.offset = 0.01f;
  s.status = ProbeStatus::kValid;
  return {s};
}

// Its image (h x w, RGB); no sample may be NaN or infinite.
inline Image render_single(const scenes::Scene& scene, const glm::vec3& origin, const ProbeSettings& s) {
  const RenderScene rs(scene);
  const ProbeOutput out = ProbeRenderer(rs, analyse_effects(scene, false), s).render_at(single_site(origin));
  EXPECT_EQ(out.stats.counters.nonfinite_samples, 0u);
  return out.mosaic;
}

}  // namespace phyir::render
