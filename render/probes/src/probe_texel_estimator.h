#pragma once
// One direction of a probe texel: a path tracer's camera ray in path mode; in cache mode the
// steps of docs/probes-estimator.md, "The texel estimator". Internal to the probe renderer.
#include <array>
#include <cstdint>
#include <limits>
#include <utility>

#include <glm/glm.hpp>

#include "phyir/render/brdf.h"
#include "phyir/render/direct_lighting.h"
#include "phyir/render/effects.h"
#include "foot_correction.h"
#include "punctual_photons.h"
#include "phyir/render/path_tracer.h"
#include "phyir/render/probe_renderer.h"
#include "radiance_cache.h"
#include "phyir/render/render_scene.h"

namespace phyir::render {

// Everything one thread needs to estimate probe texels.
class TexelEstimator {
 public:
  // Specular bounces followed before the cache takes over whatever the roughness (a mirror
  // facing a mirror would otherwise recurse to max_bounces).
  static constexpr int kMaxSpecularDepth = 3;

  // `photons` (null or empty: none) take punctual light at first hits where dense (punctual_photons.h).
  TexelEstimator(const RenderScene& scene, const Effects& effects, const ProbeSettings& settings,
                 const RadianceCache* cache, const PunctualPhotons* photons = nullptr);

  // What sample() returns: all, the emission seen first (lights; the environment on a miss),
  // or the rest; the last two are estimated with different sample counts.
  enum class Part { kAll, kEmission, kRest };

  // What a sample met that makes its texel hard (flags in sample()'s `*seen`).
  enum Seen : uint8_t { kSeenHard = 1, kSeenSky = 2 };

  // What one sample met besides its radiance (cache mode; path mode leaves them as they are).
  struct SampleNotes {
    uint8_t seen = 0;  // Seen: kSeenHard on a light (the environment included: kSeenSky too), glass or a glossy hit
    float distance = std::numeric_limits<float>::infinity();  // to its first hit
    glm::vec3 emitted{0.0f};   // the part a light seen first emits (not the environment's)
    // Its cache lookups' fill noise: each one's standard error of the sample's luminance (the
    // lookup's, times what the path carries of it) and the cells sharing it (CachedIrradiance::block).
    static constexpr int kMaxCacheReads = kMaxSpecularDepth + 1;
    int cache_reads = 0;
    std::array<std::pair<uint64_t, float>, kMaxCacheReads> cache;  // (block, sigma)
  };

  // Radiance arriving at ray.origin from -ray.direction (cache mode: `part` of it), `*notes`
  // from a default SampleNotes; first-hit lookups go through `foot`.
  // `texel_solid_angle`: the texel's, times spp / its directions where balanced
  // (PunctualPhotons::gather's `scale`); 0: no photons.
  glm::vec3 sample(const Ray& ray, uint64_t key, Part part, const FootCorrection& foot, float texel_solid_angle,
                   SampleNotes* notes, PathCounters* c) const;

 private:
  // At a probe ray's own hit only: the foot correction of its lookup, and each punctual
  // light's share the photons take there (PunctualPhotons::shares; null: none).
  struct FirstHit {
    const FootCorrection* foot = nullptr;
    const float* photon_shares = nullptr;
  };
  // Where a sample's cache lookups note their error, and the path's throughput to the current
  // vertex (what the sample's value carries of the light there).
  struct CacheTrace {
    SampleNotes* notes = nullptr;
    glm::vec3 throughput{1.0f};
    CacheTrace after(const glm::vec3& weight) const { return CacheTrace{notes, throughput * weight}; }
    // A lookup E whose `lobe` x E (E's direct part where `with_direct`) the vertex reflects.
    void note(const glm::vec3& lobe, const CachedIrradiance& E, bool with_direct) const;
  };
  glm::vec3 miss(const glm::vec3& direction) const;

  // Radiance the opaque surface at si reflects towards wo_world (docs/probes-estimator.md, "The
  // texel estimator", steps 2-5); `depth`: its scattering event from the probe's first hit
  // (< max_bounces); `first` only at that hit; lookups noted in `trace`.
  glm::vec3 reflected(const SurfaceInteraction& si, const glm::vec3& wo_world, int depth, uint64_t key, PathCounters* c,
                      const CacheTrace& trace, const FirstHit* first = nullptr) const;

  bool glossy(const BrdfParams& p) const { return p.roughness < settings_.glossy_roughness; }

  // Light y (a specular ray's hit from the event at depth - 1) reflects back along it, emission
  // excluded: glass path traced, glossy y from a glossy surface followed, else the cache's (a
  // glossy y seen from a rough one too: path regularisation, docs/probes-estimator.md, step 5).
  glm::vec3 reflected_at(const Ray& ray, const SurfaceInteraction& y, int next, int depth, uint64_t key,
                         PathCounters* c, bool from_glossy, const CacheTrace& trace) const;

  // reflected() where the cache holds direct light too (steps 2 and 3): diffuse f_d E, no ray;
  // specular by next-event estimation and a rouletted GGX ray, power heuristic at keep x pdf.
  glm::vec3 reflected_split(const ShadingPoint& x, const glm::vec3& fd, const CachedIrradiance& E, int depth,
                            uint64_t key, PathCounters* c, const float* photon_shares, const CacheTrace& trace) const;

  // A specular chain's end in the cache: (f_d + specular albedo / pi) E, the lobe as if lit
  // uniformly; where the cache holds no direct light, E's indirect part plus light sampling.
  glm::vec3 terminal(const SurfaceInteraction& si, const glm::vec3& wo_world, int depth, uint64_t key,
                     PathCounters* c, const CacheTrace& trace) const;

  // Light samples at a probe ray's own hit near a light: kNearLightSamples, or where x emits
  // (its reflection at most its albedo of the light) ceil(that x albedo), at least one.
  int near_light_samples(const SurfaceInteraction& si, const ShadingPoint& x) const;

  // The punctual lights' irradiance at x where the cache holds direct light: exact at x in
  // scenes of few punctual lights, else the cache's; less the photons' shares (may be null).
  glm::vec3 punctual_at(const ShadingPoint& x, const CachedIrradiance& E, PathCounters* c,
                        const float* photon_shares) const;

  // The cache's irradiance at the surface of x (si's hit), keyed for its fallback.
  CachedIrradiance lookup(const SurfaceInteraction& si, const ShadingPoint& x, int depth, uint64_t key,
                          PathCounters* c) const;

  // Direct light at x where the cache holds none: next-event estimation on the emissive triangles
  // (`nee`) plus the punctual lights exactly (sampled with them if many), less `photon_shares`.
  glm::vec3 near_light(const ShadingPoint& x, DirectLightOptions* nee, int depth, uint64_t key, PathCounters* c,
                       const float* photon_shares = nullptr) const;

  // Next-event estimate (direct_lighting.h): mean of options.light_samples, own streams.
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
