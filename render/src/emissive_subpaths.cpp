// LightSubpaths' subpaths from emissive triangles (light_subpaths.h, docs/light-subpaths.md):
// a point on an emitter, a cosine direction from its emitting side, the first surface it
// meets; joined to a path vertex and weighted against the next-event estimate and the BRDF
// ray that reach the same emitter point from that surface.
#include "phyir/render/light_subpaths.h"

#include <cmath>

#include "phyir/core/safe_math.h"
#include "phyir/render/brdf.h"
#include "phyir/render/frame.h"
#include "phyir/render/ray_offset.h"
#include "phyir/render/sampling.h"

namespace phyir::render {

bool LightSubpaths::sample_emissive(const glm::vec3& choice_from, const LightSubpathVariates& u, LightVertex* out,
                                    PathCounters* counters) const {
  EmissionSample z;
  if (!scene_->emitters().sample_emission(choice_from, u.emission, &z)) return false;
  const glm::vec3 local = sample_cosine_hemisphere(glm::min(u.emission_direction, glm::vec2(kOneMinusEpsilon)));
  if (!(local.z >= kMinCosine)) return false;
  const glm::vec3 direction = Frame(z.normal).to_world(local);
  ++counters->rays;
  if (!scene_->trace(Ray{spawn_origin(z.position, z.normal, direction), direction}, &out->hit) || !joinable(out->hit))
    return false;
  const glm::vec3 to_y = out->hit.position - z.position;
  const float d2 = glm::dot(to_y, to_y);
  const float cos_y = glm::dot(out->hit.geometric_normal, -direction);  // its normals face the light
  if (!(cos_y >= kMinCosine) || !(d2 > 0.0f)) return false;
  out->light = -1;
  out->choice_from = choice_from;
  out->origin = z;
  out->density = z.density * local.z * kInvPi * cos_y / d2;
  out->nee_pmf = scene_->emitters().pdf(out->hit.position, z.mesh, z.triangle, z.position);
  out->hit_guide = GuideMixture{};
  return std::isfinite(out->density) && out->density > 0.0f;
}

float LightSubpaths::emissive_competing_pdf(const PreviousVertex& previous, const glm::vec3& y, const glm::vec3& ng_y,
                                            const glm::vec3& wi, int mesh, int triangle) const {
  if (!emissive_) return 0.0f;
  const float cos_z_side = std::abs(glm::dot(ng_y, wi));  // cos_y,z: where the subpath arrives at y
  if (!(cos_z_side >= kMinCosine)) return 0.0f;
  const glm::vec3 d = y - previous.position;
  const float d2 = glm::dot(d, d);
  if (!(d2 > 0.0f)) return 0.0f;
  const float eye_area = previous.pdf * std::abs(glm::dot(ng_y, d)) / (d2 * std::sqrt(d2));  // p_x^A(y)
  if (!(eye_area > 0.0f)) return 0.0f;
  const float value =
      scene_->emitters().emission_density(previous.choice_from, mesh, triangle) * cos_z_side / (kPi * eye_area);
  return std::isfinite(value) ? value : 0.0f;
}

glm::vec3 LightSubpaths::join_emissive(const ShadingPoint& x, const LightVertex& v, Lobes lobes,
                                       const GuideMixture& guide, const glm::vec3& throughput,
                                       PathCounters* counters) const {
  const glm::vec3 to_y = v.hit.position - x.position;
  const float d2 = glm::dot(to_y, to_y);
  if (!(d2 > 0.0f)) return glm::vec3(0.0f);
  const glm::vec3 wi_world = to_y / std::sqrt(d2);
  const glm::vec3 wi = x.frame.to_local(wi_world);
  const glm::vec3 f_x = lobe_eval(x, lobes, wi);
  const float cos_x_side = glm::dot(v.hit.geometric_normal, -wi_world);  // cos_y,x
  if (glm::dot(wi_world, x.geometric_normal) <= 0.0f || !(wi.z > 0.0f) || !(max_component(f_x) > 0.0f) ||
      !(cos_x_side > 0.0f))
    return glm::vec3(0.0f);
  // The light z sends off y towards x, as y's next-event estimate would see it.
  const ShadingPoint y = shading_point(v.hit, -wi_world);
  const glm::vec3 wl_world = glm::normalize(v.origin.position - y.position);
  const glm::vec3 wl = y.frame.to_local(wl_world);
  const glm::vec3 f_y = brdf_eval(y.brdf, y.wo, wl);
  const float cos_z_side = glm::dot(v.hit.geometric_normal, wl_world);  // cos_y,z
  if (!(wl.z > 0.0f) || !can_arrive(y, wl_world) || !(max_component(f_y) > 0.0f) || !(cos_z_side >= kMinCosine))
    return glm::vec3(0.0f);
  // The three strategies' densities, in solid angle at y (light_subpaths.h).
  const float eye_area = guide.pdf(lobe_pdf(x, lobes, wi), wi_world) * cos_x_side / d2;
  const float p_sub = v.origin.density * cos_z_side / (kPi * eye_area);
  const float p_brdf = v.hit_guide.pdf(lobe_pdf(y, Lobes::kAll, wl), wl_world);
  const float w = eye_area > 0.0f ? power_heuristic(p_sub, v.nee_pmf, p_brdf) : 1.0f;
  ++counters->rays;
  const float through = scene_->accelerator().transmittance(
      shadow_ray_between(spawn_origin(x.position, x.geometric_normal, wi_world), y.position, y.geometric_normal));
  if (!(through > 0.0f)) return glm::vec3(0.0f);
  const float scale = wi.z * cos_x_side / d2 * wl.z / cos_z_side * kPi / v.origin.density * w * through;
  const glm::vec3 value = throughput * f_x * f_y * v.origin.radiance * scale;
  return is_finite(value) ? value : glm::vec3(0.0f);
}

}  // namespace phyir::render
