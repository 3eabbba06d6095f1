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
//
// Light subpaths (PathSettings::light_subpaths; docs/light-subpaths.md): a path draws one
// subpath from a point or spot light at its first scattering vertex and joins it at every
// vertex; the punctual lights' next-event estimate at the next vertex is weighted against it.
//
// Path guiding (docs/guiding.md): with a guide, every non-mirror vertex draws its next
// direction from the mixture of the BRDF and the guide (guide_mixture.h), and training paths
// record the radiance they find at each vertex into a buffer the caller gives (the renderer
// merges it into the next guide, guided_render.h). Without a guide and a buffer nothing of
// this runs and no random number is drawn for it: the image is the unguided one, bit for bit.
#include <cstdint>

#include <glm/glm.hpp>

#include "phyir/render/effects.h"
#include "phyir/render/guiding/radiance_record.h"
#include "phyir/render/guiding/sd_tree.h"
#include "phyir/render/interaction.h"
#include "phyir/render/light_subpaths.h"
#include "phyir/render/path_counters.h"
#include "phyir/render/ray.h"
#include "phyir/render/render_scene.h"

namespace phyir::render {

struct PathSettings {
  int max_bounces = 8;          // scattering events after the first hit
  int roulette_start = 3;       // bounce from which Russian roulette may end paths
  const guiding::SDTree* guide = nullptr;  // path guiding where set (not owned)
  float guide_bsdf_fraction = 0.5f;        // a: the BRDF's share of the guided mixture (the paper's)
  // Join a light subpath from the point and spot lights at every vertex (light_subpaths.h):
  // one more ray per path and per vertex where the scene has such lights, none where it has
  // not (docs/light-subpaths.md: 3.3x less variance per second on the Blender lit room).
  bool light_subpaths = true;
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
  guiding::RecordBuffer* records = nullptr;  // training: each vertex's radiance record goes here
  const LightSubpaths* subpaths = nullptr;   // joined at every vertex where set
  const PreviousVertex* previous = nullptr;  // the vertex before `hit`, where the path came from one
  // With `previous`: the light subpath its path drew there (null: it drew one that failed).
  const LightVertex* subpath = nullptr;
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
  // The same, appending the radiance the path found at its vertices to `records` (training a
  // guide; the estimate is the one the overload above returns).
  glm::vec3 radiance(const Ray& ray, uint64_t path_key, const FirstBounceSamples& first, PathCounters* counters,
                     guiding::RecordBuffer* records) const;

  // The light the surface at `hit` (found along `ray`) sends back along the ray, its own
  // emission excluded: the path continued from a known hit, with at most `max_bounces`
  // scattering events counting the hit's own, and the random streams radiance() would use
  // from that hit on. Traces no ray to the hit.
  glm::vec3 continue_from(const SurfaceInteraction& hit, const Ray& ray, uint64_t path_key, int max_bounces,
                          PathCounters* counters) const;
  // The same for a hit found by a ray drawn at a surface vertex `previous`, which drew the
  // light subpath `subpath` (null where that failed) and joined it: the path joins the same
  // subpath at its vertices and weighs the punctual lights' next-event estimates against it.
  glm::vec3 continue_from(const SurfaceInteraction& hit, const Ray& ray, const PreviousVertex& previous,
                          const LightVertex* subpath, uint64_t path_key, int max_bounces,
                          PathCounters* counters) const;

  // The light subpaths every vertex joins; null where they are off or the scene has no
  // point or spot light.
  const LightSubpaths* light_subpaths() const { return subpaths_.empty() ? nullptr : &subpaths_; }

  const Effects& effects() const { return effects_; }

 private:
  using Kernel = glm::vec3 (*)(const RenderScene&, const PathSettings&, const PathStart&, uint64_t, int, PathCounters*);
  const RenderScene* scene_;
  Effects effects_;
  PathSettings settings_;
  LightSubpaths subpaths_;
  Kernel kernel_;
};

}  // namespace phyir::render
