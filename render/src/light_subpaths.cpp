#include "phyir/render/light_subpaths.h"

#include <algorithm>
#include <cmath>

#include "phyir/core/safe_math.h"
#include "phyir/render/brdf.h"
#include "phyir/render/frame.h"
#include "phyir/render/ray_offset.h"
#include "phyir/render/sampling.h"

namespace phyir::render {

namespace {

using Type = scenes::PunctualLight::Type;

// The squared distance below which a light's choice weight stops growing: a vertex at the
// light itself would otherwise take every choice (and divide by zero).
constexpr float kMinChoiceDistance2 = 1e-6f;

// With more lights than this the choice is by power alone: a choice weighs every light, at
// each of a path's next-event estimates (as EmitterSampler::kMaxSpatialClusters bounds its own).
constexpr size_t kMaxSpatialLights = 64;

}  // namespace

LightSubpaths::LightSubpaths(const RenderScene& scene) : scene_(&scene) {
  const DeltaLights& lights = scene.emitters().delta_lights();
  entry_.assign(size_t(lights.size()), -1);
  for (int i = 0; i < lights.size(); ++i) {
    const scenes::PunctualLight& light = lights.light(i);
    if (light.type == Type::Directional || !(lights.power(i) > 0.0f)) continue;
    Light l;
    l.index = i;
    l.position = light.position;
    if (light.type == Type::Spot) {
      l.axis = glm::normalize(light.direction);
      l.cos_outer = std::cos(light.outer_cone_angle);
    }
    l.power = lights.power(i);
    entry_[size_t(i)] = int(lights_.size());
    lights_.push_back(l);
    total_power_ += l.power;
  }
}

bool LightSubpaths::joinable(const SurfaceInteraction& y) { return !is_mirror(y.brdf.roughness) && !(y.transmission > 0.0f); }

int LightSubpaths::entry_of(int light) const {
  return light >= 0 && size_t(light) < entry_.size() ? entry_[size_t(light)] : -1;
}

float LightSubpaths::choice_weight(const glm::vec3& x, size_t k) const {
  if (lights_.size() > kMaxSpatialLights) return lights_[k].power;
  const glm::vec3 d = lights_[k].position - x;
  return lights_[k].power / std::max(glm::dot(d, d), kMinChoiceDistance2);
}

float LightSubpaths::choice_pmf(const glm::vec3& x, int k) const {
  // By power over squared distance: the lights near x light what x sees.
  if (lights_.size() > kMaxSpatialLights) return total_power_ > 0.0f ? lights_[size_t(k)].power / total_power_ : 0.0f;
  float total = 0.0f;
  for (size_t i = 0; i < lights_.size(); ++i) total += choice_weight(x, i);
  return total > 0.0f ? choice_weight(x, size_t(k)) / total : 0.0f;
}

float LightSubpaths::density(const glm::vec3& choice_from, int light, const glm::vec3& y, const glm::vec3& ng_y) const {
  const int k = entry_of(light);
  if (k < 0) return 0.0f;
  const Light& l = lights_[size_t(k)];
  const glm::vec3 d = l.position - y;
  const float r2 = glm::dot(d, d);
  if (!(r2 > 0.0f)) return 0.0f;
  const float r = std::sqrt(r2);
  const float cos_y = glm::dot(ng_y, d) / r;
  if (!(cos_y > 0.0f)) return 0.0f;
  const float cos_axis = glm::dot(l.axis, -d / r);
  if (l.cos_outer > -1.0f && cos_axis < l.cos_outer) return 0.0f;
  const float value = choice_pmf(choice_from, k) * uniform_cone_pdf(cos_axis, l.cos_outer) * cos_y / r2;
  return std::isfinite(value) ? value : 0.0f;
}

float LightSubpaths::eye_weight(const PreviousVertex& previous, const ShadingPoint& y, int light, float nee_pmf) const {
  if (is_mirror(y.brdf.roughness)) return 1.0f;
  const float p_light = density(previous.choice_from, light, y.position, y.geometric_normal);
  if (!(p_light > 0.0f)) return 1.0f;
  const glm::vec3 d = y.position - previous.position;
  const float d2 = glm::dot(d, d);
  if (!(d2 > 0.0f)) return 1.0f;
  const float cos_y = std::abs(glm::dot(y.geometric_normal, d)) / std::sqrt(d2);
  const float p_eye = previous.pdf * cos_y / d2 * nee_pmf;
  return power_heuristic(p_eye, p_light);
}

bool LightSubpaths::sample(const glm::vec3& choice_from, const LightSubpathVariates& u, LightVertex* out,
                           PathCounters* counters) const {
  if (lights_.empty()) return false;
  // The light by P(l | choice_from), inverting its cumulative weights.
  float total = 0.0f;
  for (size_t k = 0; k < lights_.size(); ++k) total += choice_weight(choice_from, k);
  if (!(total > 0.0f)) return false;
  float target = u.choice * total;
  size_t k = 0;
  for (; k + 1 < lights_.size(); ++k) {
    target -= choice_weight(choice_from, k);
    if (target < 0.0f) break;
  }
  const Light& l = lights_[k];
  const glm::vec3 local = sample_uniform_cone(glm::min(u.direction, glm::vec2(kOneMinusEpsilon)), l.cos_outer);
  ++counters->rays;
  if (!scene_->trace(Ray{l.position, Frame(l.axis).to_world(local)}, &out->hit) || !joinable(out->hit)) return false;
  out->light = l.index;
  out->choice_from = choice_from;
  out->density = density(choice_from, l.index, out->hit.position, out->hit.geometric_normal);
  out->nee_pmf = scene_->emitters().delta_pmf(out->hit.position, l.index);
  return out->density > 0.0f;
}

float LightSubpaths::eye_density(const ShadingPoint& x, Lobes lobes, const GuideMixture& guide,
                                 const glm::vec3& wi_world, const LightVertex& v, float distance2) {
  const float cos_y = glm::dot(v.hit.geometric_normal, -wi_world);
  const float p_direction = guide.pdf(lobe_pdf(x, lobes, x.frame.to_local(wi_world)), wi_world);
  return p_direction * cos_y / distance2 * v.nee_pmf;
}

glm::vec3 LightSubpaths::join(const ShadingPoint& x, const LightVertex& v, Lobes lobes, const GuideMixture& guide,
                              const glm::vec3& throughput, PathCounters* counters) const {
  const glm::vec3 to_y = v.hit.position - x.position;
  const float d2 = glm::dot(to_y, to_y);
  if (!(d2 > 0.0f)) return glm::vec3(0.0f);
  const glm::vec3 wi_world = to_y / std::sqrt(d2);
  // The eye's ray would leave above x's facet (the path tracer's rule) through its lobes,
  // and arrive on the side of y the light is on.
  const glm::vec3 wi = x.frame.to_local(wi_world);
  const glm::vec3 f_x = lobe_eval(x, lobes, wi);
  if (glm::dot(wi_world, x.geometric_normal) <= 0.0f || !(wi.z > 0.0f) || !(max_component(f_x) > 0.0f) ||
      !(glm::dot(v.hit.geometric_normal, -wi_world) > 0.0f))
    return glm::vec3(0.0f);
  // L1(y -> x): the light's irradiance at y reflected towards x, as y's next-event estimate
  // would see it.
  const ShadingPoint y = shading_point(v.hit, -wi_world);
  DeltaIllumination seen;
  if (!scene_->emitters().delta_lights().illuminate(v.light, y.position, &seen)) return glm::vec3(0.0f);
  const glm::vec3 wl = y.frame.to_local(seen.wi);
  const glm::vec3 f_y = brdf_eval(y.brdf, y.wo, wl);
  if (!(wl.z > 0.0f) || !can_arrive(y, seen.wi) || !(max_component(f_y) > 0.0f)) return glm::vec3(0.0f);
  const float p_light = v.density;
  const float w = power_heuristic(p_light, eye_density(x, lobes, guide, wi_world, v, d2));
  ++counters->rays;
  const float through = scene_->accelerator().transmittance(
      shadow_ray_between(spawn_origin(x.position, x.geometric_normal, wi_world), y.position, y.geometric_normal));
  if (!(through > 0.0f)) return glm::vec3(0.0f);
  const float cos_y = glm::dot(y.geometric_normal, -wi_world);
  const glm::vec3 value = throughput * f_x * f_y * seen.irradiance * (wi.z * cos_y / d2 * wl.z * w * through / p_light);
  return is_finite(value) ? value : glm::vec3(0.0f);
}

}  // namespace phyir::render
