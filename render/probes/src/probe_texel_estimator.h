#pragma once
// How the probe renderer estimates one direction of a probe texel (docs/probes.md, "The two
// modes"): in path mode a camera ray of the path tracer; in cache mode the first hit's
// emission, its diffuse light from the radiance cache (through the foot correction at a
// probe ray's own hit), its specular light by next-event estimation and a rouletted GGX ray,
// direct light sampled per direction near the lights, glass path traced. Internal to
// probe_renderer.cpp.
#include <glm/glm.hpp>

#include "phyir/render/brdf.h"
#include "phyir/render/direct_lighting.h"
#include "phyir/render/effects.h"
#include "foot_correction.h"
#include "punctual_photons.h"
#include "phyir/render/frame.h"
#include "phyir/render/path_tracer.h"
#include "phyir/render/probe_renderer.h"
#include "radiance_cache.h"
#include "phyir/render/render_scene.h"

namespace phyir::render {

// Everything one thread needs to estimate probe texels.
class TexelEstimator {
 public:
  // Specular bounces followed before a hit is handed to the cache regardless of roughness
  // (a mirror facing a mirror would otherwise recurse to max_bounces).
  static constexpr int kMaxSpecularDepth = 3;

  // `photons` (may be null or empty) take the punctual lights' reflected light at first hits
  // where they are dense (punctual_photons.h).
  TexelEstimator(const RenderScene& scene, const Effects& effects, const ProbeSettings& settings,
                 const RadianceCache* cache, const PunctualPhotons* photons = nullptr);

  // What sample() returns: all of the radiance, or the emission seen first (lights, and the
  // environment where nothing is hit) or everything else, for estimating the two with
  // different sample counts.
  enum class Part { kAll, kEmission, kRest };

  // Radiance arriving at ray.origin from -ray.direction (cache mode: `part` of it).
  // *distance is lowered to the first hit's distance (cache mode; unchanged on a miss).
  // *emitted receives the part of the result a light seen first emits (cache mode; not the
  // environment's). Lookups at the first hit go through `foot` (foot_correction.h).
  // `texel_solid_angle`: the texel's, for the photons' share of its first hits, times the
  // scale their count is taken at (spp / the texel's directions where it was balanced, as in
  // PunctualPhotons::gather's `scale`); 0: they take none.
  glm::vec3 sample(const Ray& ray, uint64_t key, Part part, const FootCorrection& foot, float texel_solid_angle,
                   bool* saw_hard, float* distance, glm::vec3* emitted, PathCounters* c) const;

 private:
  // What applies at a probe ray's own hit only: the foot correction of its cache lookup, and
  // the share of each punctual light's value there that the photons take
  // (PunctualPhotons::shares; null where they take none).
  struct FirstHit {
    const FootCorrection* foot = nullptr;
    const float* photon_shares = nullptr;
  };
  glm::vec3 miss(const glm::vec3& direction) const;

  // Radiance the (opaque) surface at si reflects towards wo_world; `depth` = its scattering
  // event's index counted from the probe's first hit (so it is only called for depth <
  // max_bounces). Direct light is sampled here for every sample: next-event estimation and
  // one BRDF-sampled ray (the integrator's own sampling), combined by the power heuristic,
  // the punctual lights exact (near_light).
  // Indirect light: diffuse from the cache, f_d E(x); specular through the same BRDF-sampled
  // ray (f_s cos / pdf of it times the light its hit y reflects, Russian-rouletted by the
  // specular share of the sample's weight).
  // `first` (a probe ray's own hit only) corrects the lookup there and names the lights
  // the photons take.
  glm::vec3 reflected(const SurfaceInteraction& si, const glm::vec3& wo_world, int depth, uint64_t key, PathCounters* c,
                      const FirstHit* first = nullptr) const;

  bool glossy(const BrdfParams& p) const { return p.roughness < settings_.glossy_roughness; }

  // Light that y, the hit of a specular ray from a scattering event at depth - 1, reflects
  // back along it (its emission excluded): glass is path traced, a glossy y seen from a
  // glossy surface followed, any other y ends the chain in the cache. A glossy y seen in a
  // rough surface's broad lobe is not followed (path regularisation): the lights' images
  // in a small polished object, seen through a wall's lobe, are caustics a few directions
  // per texel almost never find, and then as fireflies up to 30 times the texel (measured:
  // one bench texel 0.61 against 0.29, a third of that run's squared error). Its lobe is
  // taken as lit uniformly by the cached irradiance instead.
  glm::vec3 reflected_at(const Ray& ray, const SurfaceInteraction& y, int next, int depth, uint64_t key,
                         PathCounters* c, bool from_glossy) const;

  // reflected() where the cache holds the direct light too: the diffuse part of all the
  // light is f_d E, with no ray; the specular part is estimated apart: next-event
  // estimation through f_s in every sample (one shadow ray: it finds the lights'
  // highlights, the largest specular values, so they must never carry a roulette weight),
  // and one GGX-sampled ray with its continuation taken with probability `keep`, its
  // share of the surface's albedo scaled (a wall's ~5% in a fraction of the samples). Both
  // strategies stay unbiased under the power heuristic with the GGX ray's effective
  // density keep x pdf.
  glm::vec3 reflected_split(const ShadingPoint& x, const glm::vec3& fd, const CachedIrradiance& E, int depth,
                            uint64_t key, PathCounters* c, const float* photon_shares) const;

  // Where a specular chain ends in the cache: (f_d + specular albedo / pi) E, i.e. the
  // specular lobe treated as if the light arriving were uniform: all of E where the cache
  // holds the direct light, else its indirect part plus next-event estimation (light
  // sampling alone, full BRDF).
  glm::vec3 terminal(const SurfaceInteraction& si, const glm::vec3& wo_world, int depth, uint64_t key,
                     PathCounters* c) const;

  // Light samples at a probe ray's own hit x near a light: kNearLightSamples, which serve a
  // texel whose light is the direct light x reflects. Where x emits, the texel holds its
  // emission exactly and the reflection is at most x's albedo of the light arriving: the
  // samples are scaled by that albedo, at least one (the path tracer's). A black emitting
  // wall (albedo ~5%, its Fresnel lobe) takes one, a white glowing shade nearly all.
  int near_light_samples(const SurfaceInteraction& si, const ShadingPoint& x) const;

  // The punctual lights' irradiance at x where the cache holds the direct light: exact at x
  // (punctual_light through the cosine lobe) in scenes of few punctual lights, else the cache's;
  // less the photons' shares (may be null).
  glm::vec3 punctual_at(const ShadingPoint& x, const CachedIrradiance& E, PathCounters* c,
                        const float* photon_shares) const;

  // The cache's irradiance at the surface of x (si's hit), keyed for its fallback.
  CachedIrradiance lookup(const SurfaceInteraction& si, const ShadingPoint& x, int depth, uint64_t key,
                          PathCounters* c) const;

  // The direct light at x where the cache does not hold it: a next-event estimate on the
  // emissive triangles (`nee`'s samples) and the punctual lights exactly (punctual_light:
  // one shadow ray each) in scenes of few of them, else sampled with the triangles. Chosen
  // among thousands of a lamp shade's triangles in a few samples, a bulb beside its
  // fixture lit the ceiling round it with the noise of that choice.
  // The punctual lights less the photons' shares (may be null).
  glm::vec3 near_light(const ShadingPoint& x, DirectLightOptions* nee, int depth, uint64_t key, PathCounters* c,
                       const float* photon_shares = nullptr) const;

  // A next-event estimate on the emitters (direct_lighting.h), the mean of
  // options.light_samples samples, each from its own stream.
  glm::vec3 direct_light(const ShadingPoint& x, const DirectLightOptions& options, int depth, uint64_t key,
                         PathCounters* c) const;

  const RenderScene& scene_;
  const ProbeSettings& settings_;
  const RadianceCache* cache_;
  PathTracer tracer_;  // kPath, and glass
  bool exact_punctual_;  // punctual_at() traces its own shadow rays
  const PunctualPhotons* photons_;  // null where none take any light
};

// The cache's view of a surface point: normals on the side it was seen from.
CachePoint cache_point(const SurfaceInteraction& si, const glm::vec3& shading_normal);

}  // namespace phyir::render
