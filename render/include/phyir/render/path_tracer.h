#pragma once
// Unidirectional path tracing (Kajiya 1986) with BRDF importance sampling, next-event
// estimation on emissive triangles and the environment, both combined with BRDF sampling
// by multiple importance sampling (power heuristic), and Russian roulette.
//
// The kernel is a template over the effects that need code (emitters, environment,
// transmission); PathTracer picks the instantiation from the scene's Effects, so a scene
// without glass runs no transmission code and one without emitters no light sampling.
//
// Random numbers: every bounce of every path draws from its own streams (keyed by path
// key, bounce and purpose), so enabling an effect that contributes nothing (e.g. light
// sampling in a scene without lights) never shifts the random numbers of the rest: the
// output is bit-identical, which the effects benchmark relies on.
#include <cstdint>

#include <glm/glm.hpp>

#include "phyir/render/effects.h"
#include "phyir/render/ray.h"
#include "phyir/render/render_scene.h"

namespace phyir::render {

struct PathCounters {
  uint64_t rays = 0;            // closest-hit and shadow rays
  uint64_t paths = 0;
  uint64_t nonfinite_samples = 0;  // NaN/Inf path contributions caught and zeroed

  PathCounters& operator+=(const PathCounters& o) {
    rays += o.rays;
    paths += o.paths;
    nonfinite_samples += o.nonfinite_samples;
    return *this;
  }
};

struct PathSettings {
  int max_bounces = 8;          // scattering events after the first hit
  int roulette_start = 3;       // bounce from which Russian roulette may end paths
};

// Stratified random numbers for the first scattering event of a camera path (the light
// sample and the BRDF sample), from pixel_sampler.h: across a pixel's samples they cover
// their domains evenly, where independent numbers clump. Later bounces use the path's
// independent streams.
struct FirstBounceSamples {
  float light_select = 0.5f;
  glm::vec2 light_point{0.5f};
  float lobe = 0.5f;
  glm::vec2 brdf{0.5f};
};

class PathTracer {
 public:
  // `effects` selects the kernel; pass analyse_effects(...) normally, all_effects() to
  // force every code path (benchmarks).
  PathTracer(const RenderScene& scene, const Effects& effects, const PathSettings& settings);

  // Radiance arriving at ray.origin from -ray.direction. `path_key` identifies the
  // path's random streams (derive it with path_key()). Non-finite results are counted
  // and returned as 0.
  glm::vec3 radiance(const Ray& ray, uint64_t path_key, PathCounters* counters) const;
  // The same, with the first scattering event's random numbers given.
  glm::vec3 radiance(const Ray& ray, uint64_t path_key, const FirstBounceSamples& first, PathCounters* counters) const;

  const Effects& effects() const { return effects_; }

  // Key of sample `sample` of pixel `pixel` for render seed `seed`.
  static uint64_t path_key(uint64_t seed, uint64_t pixel, uint64_t sample);

 private:
  using Kernel = glm::vec3 (*)(const RenderScene&, const PathSettings&, const Ray&, uint64_t,
                               const FirstBounceSamples*, PathCounters*);
  const RenderScene* scene_;
  Effects effects_;
  PathSettings settings_;
  Kernel kernel_;
};

}  // namespace phyir::render
