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
// key, bounce and purpose: streams.h), so enabling an effect that contributes nothing (e.g. light
// sampling in a scene without lights) never shifts the random numbers of the rest: the
// output is bit-identical, which the effects benchmark relies on.
#include <cstdint>

#include <glm/glm.hpp>

#include "phyir/render/effects.h"
#include "phyir/render/interaction.h"
#include "phyir/render/path_counters.h"
#include "phyir/render/ray.h"
#include "phyir/render/render_scene.h"

namespace phyir::render {

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

// Where a path starts (internal to PathTracer): a ray, or a hit already found along it; and
// its first bounce's random numbers, if given.
struct PathStart {
  Ray ray;
  const SurfaceInteraction* hit = nullptr;
  const FirstBounceSamples* first = nullptr;
};

class PathTracer {
 public:
  // `effects` selects the kernel; pass analyse_effects(...) normally, all_effects() to
  // force every code path (benchmarks).
  PathTracer(const RenderScene& scene, const Effects& effects, const PathSettings& settings);

  // Radiance arriving at ray.origin from -ray.direction. `path_key` identifies the
  // path's random streams (sample_key() of streams.h). Non-finite results are counted
  // and returned as 0.
  glm::vec3 radiance(const Ray& ray, uint64_t path_key, PathCounters* counters) const;
  // The same, with the first scattering event's random numbers given.
  glm::vec3 radiance(const Ray& ray, uint64_t path_key, const FirstBounceSamples& first, PathCounters* counters) const;

  // The light the surface at `hit` (found along `ray`) sends back along the ray, its own
  // emission excluded: the path continued from a known hit, with at most `max_bounces`
  // scattering events counting the hit's own, and the random streams radiance() would use
  // from that hit on. Traces no ray to the hit.
  glm::vec3 continue_from(const SurfaceInteraction& hit, const Ray& ray, uint64_t path_key, int max_bounces,
                          PathCounters* counters) const;

  const Effects& effects() const { return effects_; }

 private:
  using Kernel = glm::vec3 (*)(const RenderScene&, const PathSettings&, const PathStart&, uint64_t, int, PathCounters*);
  const RenderScene* scene_;
  Effects effects_;
  PathSettings settings_;
  Kernel kernel_;
};

}  // namespace phyir::render
