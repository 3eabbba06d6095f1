#pragma once
// Direct lighting, written once for every estimator (the path tracer, the radiance cache,
// the probe texel estimator): next-event estimation towards the scene's lights, and the
// multiple-importance weight of a BRDF-sampled ray that reaches an emitter, both with the
// power heuristic (Veach 1997). Which light a sample goes to is the EmitterSampler's choice
// (emitter_sampler.h); a new kind of light joins there and here, not in the estimators.
//
// A next-event sample draws a light point with the given variates, evaluates the asked-for
// lobes there, and traces one shadow ray. A punctual light (delta_lights.h) is weighted by
// 1: no ray can hit it. Otherwise the value is
//   throughput f(wo, wi) L_e cos / p_light, times the MIS weight p_light^2 / (p_light^2 + p_brdf^2)
// where p_light counts `light_samples` times (several light samples against one BRDF ray:
// the balance of multi-sample MIS) and p_brdf is the competing ray's density times the
// probability that the caller traces it at all.
#include <glm/glm.hpp>

#include "phyir/render/brdf.h"
#include "phyir/render/frame.h"
#include "phyir/render/guide_mixture.h"
#include "phyir/render/interaction.h"
#include "phyir/render/path_counters.h"
#include "phyir/render/render_scene.h"
#include "phyir/render/rng.h"

namespace phyir::render {

// A surface point being shaded: where it is, its frames, the direction it is seen from.
struct ShadingPoint {
  glm::vec3 position{0.0f};
  glm::vec3 shadow_lift{0.0f};                   // SurfaceInteraction::shadow_lift
  glm::vec3 geometric_normal{0.0f, 0.0f, 1.0f};  // the side shadow rays leave from
  Frame frame;                                   // shading frame (n = shading normal)
  glm::vec3 wo{0.0f, 0.0f, 1.0f};                // towards the viewer, local
  BrdfParams brdf;
};

// Whether the scene has lights to sample at all: emissive triangles or punctual lights
// (without, estimators skip next-event estimation and weight every emitter hit by 1).
inline bool has_lights(const RenderScene& scene) { return !scene.emitters().empty(); }

// The shading frame at a hit: the shading normal, unless the viewer is below it (then the
// geometric normal, which always faces the viewer).
Frame shading_frame(const SurfaceInteraction& si, const glm::vec3& wo_world);

// The shading point of a hit seen along -wo_world.
ShadingPoint shading_point(const SurfaceInteraction& si, const glm::vec3& wo_world);

// What a next-event sample is weighted through.
enum class Lobes {
  kAll,       // the whole BRDF (brdf_eval, brdf_pdf)
  kSpecular,  // the specular lobe alone (specular_eval, specular_pdf)
  kCosine,    // f = 1, p = cos / pi: irradiance (a radiance cache's estimate)
};

// f and the competing ray's density for the asked-for lobes at x (wi local).
glm::vec3 lobe_eval(const ShadingPoint& x, Lobes lobes, const glm::vec3& wi);
float lobe_pdf(const ShadingPoint& x, Lobes lobes, const glm::vec3& wi);

// Whether light from wi_world (above the shading normal's horizon) can reach x: from above
// the facet's plane always; from below it only where x was lifted onto the smooth surface
// (docs/brdf.md, "Smooth normals on coarse meshes").
bool can_arrive(const ShadingPoint& x, const glm::vec3& wi_world);

// Where a shadow ray of x towards wi_world starts, on the shaded side: its smooth-surface
// point for a light below or near the facet's plane (the terminator's band), x itself for one
// clearly above it, where the facet cannot hide the light and a BRDF-sampled ray from x
// competes: leaving from elsewhere would make the two strategies see different things (a thin
// disc whose normals are smoothed over its rim lifts its points by centimetres).
glm::vec3 shadow_origin(const ShadingPoint& x, const glm::vec3& wi_world);

// The path vertex before the one being shaded, as a multiple-importance weight needs it.
struct PreviousVertex {
  glm::vec3 position{0.0f};
  float pdf = 0.0f;  // solid-angle density of the ray from it to the shaded vertex
  // Where the path's light subpath chose its light (light_subpaths.h): its first joining vertex.
  glm::vec3 choice_from{0.0f};
};

class LightSubpaths;

struct LightVariates {
  float select = 0.5f;       // which light
  glm::vec2 point{0.5f};     // where on it
};

struct DirectLightOptions {
  Lobes lobes = Lobes::kAll;
  bool mis = true;                          // false: the light sample alone, weight 1
  float brdf_strategy_probability = 1.0f;   // the competing ray is traced this often
  int light_samples = 1;                    // light samples per competing ray (see above)
  // A sample whose unoccluded value (luminance) is below this traces its shadow ray with
  // probability value / weak, drawn from *roulette, and is divided by it (unbiased; 0: never).
  float weak = 0.0f;
  // false: the punctual lights are never chosen and every sample goes to the emissive
  // triangles, for callers that add the punctual lights exactly themselves
  // (punctual_light); the competing ray's emitter_hit_weight must be told the same.
  bool punctual = true;
  // Path guiding: the competing ray is drawn from this mixture of the lobes and a guide, and
  // its density in the weight is the mixture's (inactive: the lobes' alone).
  GuideMixture guide;
  // Light subpaths joined at the previous vertex (light_subpaths.h): a punctual light's
  // sample is weighted against them (null: weight 1, as with no competing strategy).
  const LightSubpaths* subpaths = nullptr;
  PreviousVertex previous;
};

// One next-event estimate of the light arriving straight from the emitters through the
// asked-for lobes, times `throughput`. Shadow rays are counted in counters->rays.
glm::vec3 sample_emitter_light(const RenderScene& scene, const ShadingPoint& x, const LightVariates& u,
                               const DirectLightOptions& options, const glm::vec3& throughput, Rng* roulette,
                               PathCounters* counters);

// The light the punctual lights (delta_lights.h) send through `lobes` at x, exactly: the sum
// over the lights in front of x of throughput-free f(wo, wi) E cos, one shadow ray each
// (counted in counters->rays), no random numbers. For estimators that take it apart from a
// next-event estimate with DirectLightOptions::punctual = false: a light chosen among many
// emissive triangles in a few samples is noisy; its exact value is not.
// `diffuse_elsewhere` (if given, one value per light): the share of each light's diffuse
// light at x (through the cosine lobe, or the BRDF's diffuse term) that another estimator
// takes (the probes' photons, punctual_photons.h); the rest is returned.
glm::vec3 punctual_light(const RenderScene& scene, const ShadingPoint& x, Lobes lobes, PathCounters* counters,
                         const float* diffuse_elsewhere = nullptr);

// The same towards the environment, through `lobes` (the path tracer: kAll; the radiance
// cache's fill: kCosine, irradiance): one direction by the environment's own density (u) or,
// where the scene has light portals, through them (u_portal; unused without), each chosen
// with probability 1/2 by u_portal.z and weighted against the other and the BRDF's density
// by the power heuristic (environment_hit_weight is the BRDF ray's weight against both). With an
// active `guide`, the competing ray's density is the mixture's (DirectLightOptions::guide).
glm::vec3 sample_environment_light(const RenderScene& scene, const ShadingPoint& x, const glm::vec3& u,
                                   const glm::vec3& u_portal, const glm::vec3& throughput, PathCounters* counters,
                                   Lobes lobes = Lobes::kAll, const GuideMixture& guide = {});

// The MIS weight of a BRDF-sampled ray from `from` with density `brdf_pdf` (solid angle,
// the probability of tracing it included) that hits the emitter at `hit`, against
// `light_samples` next-event samples of the same scattering event, which chose among the
// punctual lights too or (punctual = false) not.
float emitter_hit_weight(const RenderScene& scene, const glm::vec3& from, float brdf_pdf, const SurfaceInteraction& hit,
                         int light_samples = 1, bool punctual = true);

// The same for a ray from `from` that leaves the scene and sees the environment in
// `direction`, against the environment's sample and (with portals) the portals'.
float environment_hit_weight(const RenderScene& scene, const glm::vec3& from, float brdf_pdf, const glm::vec3& direction);

}  // namespace phyir::render
