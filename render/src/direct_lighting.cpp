#include "phyir/render/direct_lighting.h"

#include <algorithm>
#include <cmath>

#include "phyir/core/safe_math.h"
#include "phyir/render/light_subpaths.h"
#include "phyir/render/ray_offset.h"

namespace phyir::render {

Frame shading_frame(const SurfaceInteraction& si, const glm::vec3& wo_world) {
  if (glm::dot(si.shading_normal, wo_world) > 0.0f) return Frame(si.shading_normal);
  return Frame(si.geometric_normal);
}

ShadingPoint shading_point(const SurfaceInteraction& si, const glm::vec3& wo_world) {
  ShadingPoint x;
  x.position = si.position;
  x.shadow_lift = si.shadow_lift;
  x.geometric_normal = si.geometric_normal;
  x.frame = shading_frame(si, wo_world);
  x.wo = x.frame.to_local(wo_world);
  x.brdf = si.brdf;
  return x;
}

glm::vec3 lobe_eval(const ShadingPoint& x, Lobes lobes, const glm::vec3& wi) {
  switch (lobes) {
    case Lobes::kAll: return brdf_eval(x.brdf, x.wo, wi);
    case Lobes::kSpecular: return specular_eval(x.brdf, x.wo, wi);
    default: return wi.z >= kMinCosine ? glm::vec3(1.0f) : glm::vec3(0.0f);
  }
}

float lobe_pdf(const ShadingPoint& x, Lobes lobes, const glm::vec3& wi) {
  switch (lobes) {
    case Lobes::kAll: return brdf_pdf(x.brdf, x.wo, wi);
    case Lobes::kSpecular: return specular_pdf(x.brdf, x.wo, wi);
    default: return wi.z * kInvPi;
  }
}

bool can_arrive(const ShadingPoint& x, const glm::vec3& wi_world) {
  return glm::dot(wi_world, x.geometric_normal) > 0.0f || x.shadow_lift != glm::vec3(0.0f);
}

namespace {

// A light at least this far above the facet's plane (the cosine with its normal) is seen from
// the point itself; nearer the plane the smooth-surface lift blends in (Cycles' default
// "shadow terminator geometry offset").
constexpr float kLiftCutoff = 0.1f;

}  // namespace

glm::vec3 shadow_origin(const ShadingPoint& x, const glm::vec3& wi_world) {
  const float above = glm::dot(wi_world, x.geometric_normal);
  const float lift = std::clamp(1.0f - above / kLiftCutoff, 0.0f, 1.0f);
  return offset_ray_origin(x.position + lift * x.shadow_lift, x.geometric_normal);
}

namespace {

// The shadow ray of a light sample: to a point on an emitter, to a point light, or out of
// the scene towards a directional light; it always leaves on the shaded side of the facet.
Ray shadow_ray(const ShadingPoint& x, const EmitterSample& ls) {
  if (std::isinf(ls.distance)) return Ray{shadow_origin(x, ls.wi), ls.wi};
  return shadow_ray_between(shadow_origin(x, ls.wi), ls.position, ls.normal);
}

}  // namespace

glm::vec3 sample_emitter_light(const RenderScene& scene, const ShadingPoint& x, const LightVariates& u,
                               const DirectLightOptions& options, const glm::vec3& throughput, Rng* roulette,
                               PathCounters* counters) {
  EmitterSample ls;
  if (!scene.emitters().sample(x.position, u.select, u.point, &ls, options.punctual) || !(ls.pdf > 0.0f) ||
      !(max_component(ls.radiance) > 0.0f))
    return glm::vec3(0.0f);
  const glm::vec3 wi = x.frame.to_local(ls.wi);
  const glm::vec3 f = lobe_eval(x, options.lobes, wi);
  // f > 0 implies wi.z >= kMinCosine for every lobe.
  if (!(wi.z > 0.0f) || !can_arrive(x, ls.wi) || !(max_component(f) > 0.0f)) return glm::vec3(0.0f);
  auto value = [&] {
    // A punctual light cannot be hit by the competing ray: no MIS, unless a light subpath
    // joined at the previous vertex competes.
    float w = 1.0f;
    if (options.mis && !ls.delta)
      w = power_heuristic(float(options.light_samples) * ls.pdf,
                          options.brdf_strategy_probability * options.guide.pdf(lobe_pdf(x, options.lobes, wi), ls.wi));
    else if (ls.delta && options.subpaths)
      w = options.subpaths->eye_weight(options.previous, x, ls.light, ls.pdf);
    return throughput * f * ls.radiance * (wi.z * w / ls.pdf);
  };
  auto visible = [&] {
    ++counters->rays;
    return scene.accelerator().transmittance(shadow_ray(x, ls));
  };
  // Without the roulette the value is only needed where the light is in view.
  if (!(options.weak > 0.0f)) {
    const float through = visible();
    return through > 0.0f ? through * value() : glm::vec3(0.0f);
  }
  const glm::vec3 contribution = value();
  float keep = 1.0f;
  if (const float y = luminance(contribution); y < options.weak) {
    keep = y / options.weak;
    if (!(roulette->next_float() < keep)) return glm::vec3(0.0f);
  }
  return contribution * (visible() / keep);
}

glm::vec3 punctual_light(const RenderScene& scene, const ShadingPoint& x, Lobes lobes, PathCounters* counters,
                         const float* diffuse_elsewhere) {
  const DeltaLights& lights = scene.emitters().delta_lights();
  glm::vec3 sum(0.0f);
  for (int light = 0; light < lights.size(); ++light) {
    const float elsewhere = diffuse_elsewhere && lobes != Lobes::kSpecular ? diffuse_elsewhere[light] : 0.0f;
    DeltaIllumination seen;
    if (!lights.illuminate(light, x.position, &seen)) continue;
    const glm::vec3 wi = x.frame.to_local(seen.wi);
    glm::vec3 f = lobe_eval(x, lobes, wi);
    if (elsewhere > 0.0f)
      f -= elsewhere * (lobes == Lobes::kAll ? Fd_Lambert(x.brdf.base_color, x.brdf.metalness) : f);
    if (!(wi.z > 0.0f) || !can_arrive(x, seen.wi) || !(max_component(f) > 0.0f)) continue;
    EmitterSample ls;
    ls.position = seen.position;
    ls.normal = -seen.wi;
    ls.wi = seen.wi;
    ls.distance = seen.distance;
    ++counters->rays;
    sum += f * seen.irradiance * (wi.z * scene.accelerator().transmittance(shadow_ray(x, ls)));
  }
  return is_finite(sum) ? sum : glm::vec3(0.0f);
}

namespace {

// With light portals, the environment's next-event sample goes through them with this
// probability, else by the environment's own density.
constexpr float kPortalStrategyProbability = 0.5f;

// One environment sample in direction wi_world of radiance Le, drawn with density `pdf`,
// against other_pdf() (the other environment strategy's density for it, asked only of an
// unoccluded sample) and the BRDF's.
template <class OtherPdf>
glm::vec3 environment_sample(const RenderScene& scene, const ShadingPoint& x, Lobes lobes, const GuideMixture& guide,
                             const glm::vec3& wi_world, const glm::vec3& Le, float pdf, const OtherPdf& other_pdf,
                             const glm::vec3& throughput, PathCounters* counters) {
  const glm::vec3 wi = x.frame.to_local(wi_world);
  const glm::vec3 f = lobe_eval(x, lobes, wi);
  if (!(wi.z > 0.0f) || !can_arrive(x, wi_world) || !(max_component(f) > 0.0f)) return glm::vec3(0.0f);
  ++counters->rays;
  const float through = scene.accelerator().transmittance(Ray{shadow_origin(x, wi_world), wi_world});
  if (!(through > 0.0f)) return glm::vec3(0.0f);
  const float w = power_heuristic(pdf, guide.pdf(lobe_pdf(x, lobes, wi), wi_world), other_pdf());
  return throughput * f * Le * (wi.z * w * through / pdf);
}

}  // namespace

glm::vec3 sample_environment_light(const RenderScene& scene, const ShadingPoint& x, const glm::vec3& u,
                                   const glm::vec3& u_portal, const glm::vec3& throughput, PathCounters* counters,
                                   Lobes lobes, const GuideMixture& guide) {
  const EnvironmentLight* environment = scene.environment();
  if (!environment) return glm::vec3(0.0f);
  const EnvironmentPortals& portals = scene.portals();
  glm::vec3 wi_world, Le;
  float pdf;
  if (portals.empty()) {
    if (!environment->sample(u, &wi_world, &Le, &pdf) || !(pdf > 0.0f)) return glm::vec3(0.0f);
    if (environment->positional()) Le = environment->radiance_at(x.position, wi_world);
    return environment_sample(scene, x, lobes, guide, wi_world, Le, pdf, [] { return 0.0f; }, throughput, counters);
  }
  // One strategy, each chosen with probability 1/2 (one shadow ray, as without portals): the
  // densities in every weight are the chosen ones', halved (environment_hit_weight too).
  const float c = kPortalStrategyProbability;
  if (u_portal.z < c) {
    const glm::vec3 u_through(u_portal.x, u_portal.y, u_portal.z / c);
    if (!portals.sample(x.position, u_through, &wi_world, &pdf)) return glm::vec3(0.0f);
    const glm::vec3 d = wi_world;
    auto environment_pdf = [&] { return (1.0f - c) * environment->pdf(d); };
    return environment_sample(scene, x, lobes, guide, d, environment->radiance_at(x.position, d), c * pdf, environment_pdf, throughput,
                              counters);
  }
  if (!environment->sample(u, &wi_world, &Le, &pdf) || !(pdf > 0.0f)) return glm::vec3(0.0f);
  if (environment->positional()) Le = environment->radiance_at(x.position, wi_world);
  const glm::vec3 d = wi_world;
  auto portal_pdf = [&] { return c * portals.pdf(x.position, d); };
  return environment_sample(scene, x, lobes, guide, d, Le, (1.0f - c) * pdf, portal_pdf, throughput, counters);
}

float emitter_hit_weight(const RenderScene& scene, const glm::vec3& from, float brdf_pdf, const SurfaceInteraction& hit,
                         int light_samples, bool punctual) {
  return power_heuristic(brdf_pdf, float(light_samples) *
                                       scene.emitters().pdf(from, hit.mesh, hit.triangle, hit.position, punctual));
}

float environment_hit_weight(const RenderScene& scene, const glm::vec3& from, float brdf_pdf, const glm::vec3& direction) {
  if (scene.portals().empty()) return power_heuristic(brdf_pdf, scene.environment()->pdf(direction));
  const float c = kPortalStrategyProbability;
  return power_heuristic(brdf_pdf, (1.0f - c) * scene.environment()->pdf(direction),
                         c * scene.portals().pdf(from, direction));
}

}  // namespace phyir::render
