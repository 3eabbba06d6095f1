#pragma once
// Renders one view: the colour estimate (spp paths per pixel, box-filtered over the pixel)
// and, separately, the G-buffer from one ray through each pixel centre. The two never
// share random numbers, so turning AOVs off cannot change color.exr. Work is split into
// 16x16 tiles run by oneTBB; every pixel's samples are summed in a fixed order from
// streams keyed by (seed, pixel, sample), so output is bit-identical for any thread count.
#include <cstdint>

#include <nlohmann/json.hpp>

#include "phyir/render/camera.h"
#include "phyir/render/effects.h"
#include "phyir/render/film.h"
#include "phyir/render/guided_render.h"
#include "phyir/render/path_tracer.h"
#include "phyir/render/render_scene.h"

namespace phyir::render {

struct RenderSettings {
  int spp = 64;
  uint64_t seed = 0;
  PathSettings path;
  bool aovs = true;
  bool force_all_effects = false;  // run every kernel feature (benchmarks; same output)
  bool progress = true;
  GuidingSettings guiding;         // path guiding of the colour (off: the unguided image)
};

struct RenderStats {
  double color_seconds = 0.0;
  double aov_seconds = 0.0;
  PathCounters counters;
  uint64_t aov_rays = 0;
  GuidingStats guiding;
  nlohmann::json to_json() const;
};

struct RenderOutput {
  Film film;
  Effects effects;
  RenderStats stats;
};

// The sum of samples [first, first + count) of pixel (x, y) of a `width`-wide image: their
// keys, the pixel's stratified first-bounce numbers, one path each. `records`: training a guide.
glm::dvec3 sum_pixel_samples(const PathTracer& tracer, const CameraModel& camera, uint64_t seed, int x, int y,
                             int width, int first, int count, PathCounters* counters,
                             guiding::RecordBuffer* records = nullptr);

RenderOutput render_view(const RenderScene& scene, const CameraModel& camera, const RenderSettings& settings);

}  // namespace phyir::render
