#include "probe_texel_estimator.h"

#include <algorithm>
#include <cmath>
#include <vector>

#include "phyir/core/safe_math.h"
#include "phyir/render/ray_offset.h"
#include "phyir/render/rng.h"
#include "phyir/render/sampling.h"

namespace phyir::render {

namespace {

// Streams of the cache-mode shading, per specular depth (distinct from the path tracer's
// purposes 1..5 and the cache's 101..103).
enum Purpose : uint64_t {
  kLightSample = 201,
  kBrdfSample = 202,
  kLookup = 203,
  kGlassContinuation = 204,
  kSpecularRoulette = 205
};

// The light reflected at a BRDF-sampled ray's hit is needed for the specular part of the
// sample's weight only (the diffuse part of the indirect light is the cache's); it is
// evaluated with probability min(1, kSpecularKeepScale x that part's share of the weight),
// weighted by the inverse: a wall's cosine-lobe sample (specular share ~2%) evaluates it in
// 1/8 of the samples (the floor, so no sample is weighted by more than 8), a glossy or
// metal lobe in every sample.
constexpr float kSpecularKeepScale = 4.0f;
constexpr float kMinSpecularKeep = 0.125f;

// Light samples of the next-event estimate at a probe ray's own hit near a light (where
// direct light is not cached): there the direct light of a thin or nearby emitter varies
// most from one direction to the next (measured: the ceiling beside a light fixture).
constexpr int kNearLightSamples = 8;

// Where the cache holds the direct light, a specular next-event sample adding less than this
// fraction of the diffuse light traces its shadow ray with probability (its share / this)
// (direct_light). Measured: 0.05 saves 86 M of 371 M rays on the bench for 1% more error;
// 0.15 only 13 M more, for 6% more error.
constexpr float kWeakShadowFraction = 0.05f;

Rng shading_rng(uint64_t key, int depth, Purpose purpose) {
  return Rng(mix64(key ^ mix64(uint64_t(purpose) * 64 + uint64_t(depth))), purpose);
}
uint64_t derived_key(uint64_t key, int depth, Purpose purpose) {
  return mix64(key ^ mix64(uint64_t(purpose) * 64 + uint64_t(depth) + 7));
}

// The path tracer's rule (path_tracer.cpp): the shading normal unless the viewer is below it.
Frame shading_frame(const SurfaceInteraction& si, const glm::vec3& wo_world) {
  if (glm::dot(si.shading_normal, wo_world) > 0.0f) return Frame(si.shading_normal);
  return Frame(si.geometric_normal);
}

BrdfParams clamped(const BrdfParams& p) {
  return {glm::clamp(p.base_color, glm::vec3(0.0f), glm::vec3(1.0f)), clamp01(p.roughness), clamp01(p.metalness)};
}

// f_s alone: the BRDF minus its Lambert term (the same code as the integrator's f_r).
glm::vec3 specular_eval(const BrdfParams& p, const glm::vec3& wo, const glm::vec3& wi) {
  return glm::max(brdf_eval(p, wo, wi) - Fd_Lambert(p.base_color, p.metalness), glm::vec3(0.0f));
}

// Density of GGX half-vector sampling (eq. 18, specular lobe alone) in wi.
float specular_pdf(const glm::vec3& wo, const glm::vec3& wi, float alpha) {
  if (!(wo.z >= kMinCosine) || !(wi.z >= kMinCosine)) return 0.0f;
  const glm::vec3 s = wo + wi;
  const float len = std::sqrt(glm::dot(s, s));
  if (!(len > 0.0f)) return 0.0f;
  const float NoH = s.z / len;
  const float VoH = 0.5f * len;  // as brdf.cpp computes it
  return D_GGX(NoH, alpha) * NoH / (4.0f * VoH);
}

// Directional albedo of the specular lobe alone towards wo (from the table below).
glm::vec3 specular_albedo(const BrdfParams& p, float NoV) {
  const glm::vec2 terms = specular_albedo_terms(NoV, p.roughness);
  const glm::vec3 F0 = specular_F0(p.base_color, p.metalness);
  return F0 * terms.x + (glm::vec3(1.0f) - F0) * terms.y;
}

struct SpecularAlbedoTable {
  static constexpr int kSize = 32;  // nodes over n.v in [0,1] and R in [0,1]
  std::vector<glm::vec2> terms;     // (F0 = 1, F0 = 0), n.v-major

  SpecularAlbedoTable() : terms(size_t(kSize) * kSize) {
    constexpr int kStrata = 32;  // 32 x 32 stratified GGX samples per node
    const BrdfParams white{glm::vec3(1.0f), 0.0f, 1.0f}, black{glm::vec3(0.0f), 0.0f, 1.0f};
    for (int i = 0; i < kSize; ++i) {
      const float NoV = std::max(float(i) / (kSize - 1), 1e-3f);
      const glm::vec3 wo(std::sqrt(1.0f - NoV * NoV), 0.0f, NoV);
      for (int j = 0; j < kSize; ++j) {
        const float R = float(j) / (kSize - 1);
        glm::dvec2 sum(0.0);
        if (is_mirror(R)) {
          const float k = (R + 1.0f) * (R + 1.0f) / 8.0f;
          const float G1 = G1_SmithSchlick(NoV, k);
          sum = glm::dvec2(F_SchlickSG(glm::vec3(1.0f), NoV).x, F_SchlickSG(glm::vec3(0.0f), NoV).x) * double(G1 * G1);
        } else {
          BrdfParams w = white, b = black;
          w.roughness = b.roughness = R;
          for (int s = 0; s < kStrata * kStrata; ++s) {
            const glm::vec2 u((s % kStrata + 0.5f) / kStrata, (s / kStrata + 0.5f) / kStrata);
            const glm::vec3 h = sample_ggx_half_vector(u, R * R);
            const glm::vec3 wi = safe_normalize(2.0f * glm::dot(wo, h) * h - wo, glm::vec3(0, 0, -1));
            const float pdf = specular_pdf(wo, wi, R * R);
            if (!(pdf > 0.0f)) continue;
            sum += glm::dvec2(brdf_eval(w, wo, wi).x, brdf_eval(b, wo, wi).x) * double(wi.z / pdf);
          }
          sum /= double(kStrata * kStrata);
        }
        terms[size_t(i) * kSize + j] = glm::vec2(sum);
      }
    }
  }

  glm::vec2 lookup(float NoV, float R) const {
    const float x = clamp01(NoV) * (kSize - 1), y = clamp01(R) * (kSize - 1);
    const int i = std::min(int(x), kSize - 2), j = std::min(int(y), kSize - 2);
    const float fx = x - i, fy = y - j;
    auto at = [&](int a, int b) { return terms[size_t(a) * kSize + b]; };
    return (1 - fx) * ((1 - fy) * at(i, j) + fy * at(i, j + 1)) +
           fx * ((1 - fy) * at(i + 1, j) + fy * at(i + 1, j + 1));
  }
};

}  // namespace

CachePoint cache_point(const SurfaceInteraction& si, const glm::vec3& shading_normal) {
  return CachePoint{si.position, shading_normal, si.geometric_normal};
}

glm::vec2 specular_albedo_terms(float NoV, float roughness) {
  static const SpecularAlbedoTable table;
  return table.lookup(NoV, roughness);
}

TexelEstimator::TexelEstimator(const RenderScene& scene, const Effects& effects, const ProbeSettings& settings,
                               const RadianceCache* cache)
    : scene_(scene), settings_(settings), cache_(cache), full_(scene, effects, settings.path) {
  for (int d = 0; d <= kMaxSpecularDepth; ++d) {
    PathSettings s = settings.path;
    s.max_bounces = std::max(settings.path.max_bounces - d, 0);
    tracers_[d] = std::make_unique<PathTracer>(scene, effects, s);
  }
}

glm::vec3 TexelEstimator::sample(const Ray& ray, uint64_t key, Part part, const FootCorrection& foot, bool* saw_hard,
                                 float* distance, glm::vec3* emitted, PathCounters* c) const {
  *emitted = glm::vec3(0.0f);
  if (settings_.mode == ProbeMode::kPath) return full_.radiance(ray, key, c);
  if (part == Part::kEmission) {  // most of these rays: a light texel's many directions
    glm::vec3 Le;
    float t = 0.0f;
    ++c->rays;
    if (!scene_.trace_emission(ray, &Le, &t)) return miss(ray.direction);
    *distance = std::min(*distance, t);
    *emitted = Le;
    return Le;
  }
  SurfaceInteraction si;
  ++c->rays;
  if (!scene_.trace(ray, &si)) return part == Part::kRest ? glm::vec3(0.0f) : miss(ray.direction);
  *distance = std::min(*distance, si.distance);
  const glm::vec3 Le = si.emits ? si.emission : glm::vec3(0.0f);
  // The texel sees something small and bright or hard to sample: a light, glass, or a
  // glossy surface (whose highlights are small images of the lights).
  if (si.emits || si.transmission > 0.0f || si.brdf.roughness < settings_.glossy_roughness) *saw_hard = true;
  const glm::vec3 L = part == Part::kAll ? Le : glm::vec3(0.0f);
  *emitted = L;
  if (settings_.path.max_bounces < 1) return L;
  if (si.transmission > 0.0f) {  // glass: path traced whole (its emission at full weight)
    const glm::vec3 all = full_.radiance(ray, key, c);
    return part == Part::kAll ? all : glm::max(all - Le, glm::vec3(0.0f));
  }
  return L + reflected(si, -ray.direction, 0, key, c, &foot);
}

glm::vec3 TexelEstimator::miss(const glm::vec3& direction) const {
  return scene_.environment() ? scene_.environment()->radiance(direction) : glm::vec3(0.0f);
}

glm::vec3 TexelEstimator::reflected(const SurfaceInteraction& si, const glm::vec3& wo_world, int depth, uint64_t key,
                                    PathCounters* c, const FootCorrection* foot) const {
  const Frame frame = shading_frame(si, wo_world);
  const glm::vec3 wo = frame.to_local(wo_world);
  if (!(wo.z >= kMinCosine)) return glm::vec3(0.0f);
  const BrdfParams p = clamped(si.brdf);
  const glm::vec3& ng = si.geometric_normal;
  const glm::vec3 fd = Fd_Lambert(p.base_color, p.metalness);
  CachedIrradiance E = cache_->lookup(cache_point(si, frame.n), derived_key(key, depth, kLookup), c);
  if (foot) foot->apply(si.position, frame.n, &E);
  if (E.has_direct && !is_mirror(p.roughness)) return reflected_split(si, frame, wo, p, fd, E, depth, key, c);
  glm::vec3 L(0.0f);
  if (max_component(fd) > 0.0f) L += fd * E.indirect;
  const bool emitters = !scene_.emitters().empty();

  // Next-event estimation on the emitters, full BRDF: several samples at a probe ray's own
  // hit (near a light the texel's noise is mostly this estimate's), one deeper.
  const int light_samples = depth == 0 ? kNearLightSamples : 1;
  if (emitters) L += direct_light(si, frame, wo, p, Lobes::kAll, depth, key, /*mis=*/true, c, 1.0f, light_samples);

  // The control variate of reflected_split(), for every sample of a rough surface (the
  // roulette below depends on the sample, so it cannot be the condition).
  const int next = depth + 1;
  const bool controlled = next < settings_.path.max_bounces && p.roughness >= settings_.glossy_roughness;
  const glm::vec3 uniform = controlled ? E.indirect * kInvPi : glm::vec3(0.0f);
  if (controlled) L += specular_albedo(p, wo.z) * uniform;

  // One direction from the BRDF.
  Rng rng = shading_rng(key, depth, kBrdfSample);
  const float u_lobe = rng.next_float();
  BrdfSample bs;
  if (!brdf_sample(p, wo, u_lobe, rng.next_2d(), &bs)) return L;
  const glm::vec3 wi_world = frame.to_world(bs.wi);
  if (glm::dot(wi_world, ng) <= 0.0f) return L;  // leaks below the surface: dropped, as the integrator does
  // The part of the sample's weight that belongs to the specular lobe (the diffuse part of
  // the indirect light comes from the cache).
  const glm::vec3 weight_specular = bs.delta ? bs.weight : specular_eval(p, wo, bs.wi) * safe_div(bs.wi.z, bs.pdf);
  const Ray ray{spawn_origin(si.position, ng, wi_world), wi_world};
  SurfaceInteraction y;
  ++c->rays;
  if (!scene_.trace(ray, &y)) return L + weight_specular * (miss(wi_world) - uniform);  // the diffuse share is in E
  if (y.emits) {
    const float w = (emitters && !bs.delta)
                        ? power_heuristic(bs.pdf, float(light_samples) * scene_.emitters().pdf(si.position, y.mesh,
                                                                                               y.triangle, y.position))
                        : 1.0f;
    L += bs.weight * y.emission * w;
  }
  if (next >= settings_.path.max_bounces || !(max_component(weight_specular) > 0.0f)) return L;
  const float share = safe_div(luminance(weight_specular), luminance(bs.weight));
  const float keep = std::clamp(kSpecularKeepScale * share, kMinSpecularKeep, 1.0f);
  if (keep < 1.0f && !(shading_rng(key, depth, kSpecularRoulette).next_float() < keep)) return L;
  return L + weight_specular * (reflected_at(ray, y, next, depth, key, c, glossy(p)) - uniform) / keep;
}

glm::vec3 TexelEstimator::reflected_at(const Ray& ray, const SurfaceInteraction& y, int next, int depth, uint64_t key,
                                       PathCounters* c, bool from_glossy) const {
  const glm::vec3 Le = y.emits ? y.emission : glm::vec3(0.0f);
  if (y.transmission > 0.0f) {
    // Glass: the path tracer from here (it re-adds y's emission at full weight: removed).
    return glm::max(
        tracers_[std::min(next, kMaxSpecularDepth)]->radiance(ray, derived_key(key, depth, kGlassContinuation), c) - Le,
        glm::vec3(0.0f));
  }
  if (from_glossy && y.brdf.roughness < settings_.glossy_roughness && next < kMaxSpecularDepth)
    return reflected(y, -ray.direction, next, key, c);
  return terminal(y, -ray.direction, next, key, c);
}

glm::vec3 TexelEstimator::reflected_split(const SurfaceInteraction& si, const Frame& frame, const glm::vec3& wo,
                                          const BrdfParams& p, const glm::vec3& fd, const CachedIrradiance& E,
                                          int depth, uint64_t key, PathCounters* c) const {
  glm::vec3 L = fd * (E.indirect + E.direct);
  const glm::vec3 albedo = specular_albedo(p, wo.z);
  const float albedo_s = luminance(albedo);
  const float share = safe_div(albedo_s, albedo_s + kPi * luminance(fd));
  if (!(share > 0.0f)) return L;
  const float keep = std::clamp(kSpecularKeepScale * share, kMinSpecularKeep, 1.0f);
  const bool emitters = !scene_.emitters().empty();
  // Its shadow ray is rouletted where the sample adds less than a small fraction of the
  // diffuse light (a rough wall away from the lights' highlights).
  const float weak = kWeakShadowFraction * luminance(L);
  if (emitters) L += direct_light(si, frame, wo, p, Lobes::kSpecular, depth, key, /*mis=*/true, c, keep, 1, weak);
  const int next = depth + 1;
  // Control variate (rouletted rays only): the specular lobe under uniform light of the
  // cached mean radiance E.indirect / pi is known exactly; the ray estimates only the
  // difference between the light it finds and that mean, so a skipped ray costs far less.
  const glm::vec3 uniform = (keep < 1.0f && next < settings_.path.max_bounces) ? E.indirect * kInvPi : glm::vec3(0.0f);
  L += albedo * uniform;
  if (keep < 1.0f && !(shading_rng(key, depth, kSpecularRoulette).next_float() < keep)) return L;

  const float alpha = p.roughness * p.roughness;
  Rng rng = shading_rng(key, depth, kBrdfSample);
  const glm::vec3 h = sample_ggx_half_vector(rng.next_2d(), alpha);
  const glm::vec3 wi = safe_normalize(2.0f * glm::dot(wo, h) * h - wo, glm::vec3(0, 0, -1));
  const float pdf = keep * specular_pdf(wo, wi, alpha);
  const glm::vec3 wi_world = frame.to_world(wi);
  const glm::vec3& ng = si.geometric_normal;
  if (!(pdf > 0.0f) || !(glm::dot(wi_world, ng) > 0.0f)) return L;
  const glm::vec3 weight = specular_eval(p, wo, wi) * safe_div(wi.z, pdf);
  if (!(max_component(weight) > 0.0f)) return L;
  const Ray ray{spawn_origin(si.position, ng, wi_world), wi_world};
  SurfaceInteraction y;
  ++c->rays;
  if (!scene_.trace(ray, &y)) return L + weight * (miss(wi_world) - uniform);
  if (y.emits) {
    const float w =
        emitters ? power_heuristic(pdf, scene_.emitters().pdf(si.position, y.mesh, y.triangle, y.position)) : 1.0f;
    L += weight * y.emission * w;
  }
  if (next < settings_.path.max_bounces) L += weight * (reflected_at(ray, y, next, depth, key, c, glossy(p)) - uniform);
  return L;
}

glm::vec3 TexelEstimator::terminal(const SurfaceInteraction& si, const glm::vec3& wo_world, int depth, uint64_t key,
                                   PathCounters* c) const {
  const Frame frame = shading_frame(si, wo_world);
  const glm::vec3 wo = frame.to_local(wo_world);
  if (!(wo.z >= kMinCosine)) return glm::vec3(0.0f);
  const BrdfParams p = clamped(si.brdf);
  glm::vec3 L(0.0f);
  const glm::vec2 terms = specular_albedo_terms(wo.z, p.roughness);
  const glm::vec3 F0 = specular_F0(p.base_color, p.metalness);
  const glm::vec3 albedo = F0 * terms.x + (glm::vec3(1.0f) - F0) * terms.y;
  const glm::vec3 lobe = Fd_Lambert(p.base_color, p.metalness) + albedo * kInvPi;
  const CachedIrradiance E = cache_->lookup(cache_point(si, frame.n), derived_key(key, depth, kLookup), c);
  if (E.has_direct) return lobe * (E.indirect + E.direct);  // the whole lobe as if lit uniformly
  // Light sampling alone: no BRDF-sampled ray at a chain's end competes for the emitters.
  if (!scene_.emitters().empty()) L += direct_light(si, frame, wo, p, Lobes::kAll, depth, key, /*mis=*/false, c);
  return L + lobe * E.indirect;
}

glm::vec3 TexelEstimator::direct_light(const SurfaceInteraction& si, const Frame& frame, const glm::vec3& wo,
                                       const BrdfParams& p, Lobes lobes, int depth, uint64_t key, bool mis,
                                       PathCounters* c, float brdf_strategy_probability, int count, float weak) const {
  glm::vec3 sum(0.0f);
  for (int k = 0; k < count; ++k)
    sum += light_sample(si, frame, wo, p, lobes, k == 0 ? key : mix64(key ^ uint64_t(k)), depth, mis, c,
                        brdf_strategy_probability, count, weak);
  return sum / float(count);
}

glm::vec3 TexelEstimator::light_sample(const SurfaceInteraction& si, const Frame& frame, const glm::vec3& wo,
                                       const BrdfParams& p, Lobes lobes, uint64_t key, int depth, bool mis,
                                       PathCounters* c, float brdf_strategy_probability, int count, float weak) const {
  Rng rng = shading_rng(key, depth, kLightSample);
  const float u_select = rng.next_float();
  const glm::vec2 u_point = rng.next_2d();
  EmitterSample ls;
  if (!scene_.emitters().sample(si.position, u_select, u_point, &ls) || !(ls.pdf > 0.0f) ||
      !(max_component(ls.radiance) > 0.0f))
    return glm::vec3(0.0f);
  const glm::vec3 wi = frame.to_local(ls.wi);
  const bool all = lobes == Lobes::kAll;
  const glm::vec3 f = all ? brdf_eval(p, wo, wi) : specular_eval(p, wo, wi);
  const glm::vec3& ng = si.geometric_normal;
  if (!(wi.z > 0.0f) || !(glm::dot(ls.wi, ng) > 0.0f) || !(max_component(f) > 0.0f)) return glm::vec3(0.0f);
  const float pdf_brdf =
      brdf_strategy_probability * (all ? brdf_pdf(p, wo, wi) : specular_pdf(wo, wi, p.roughness * p.roughness));
  const float w = mis ? power_heuristic(float(count) * ls.pdf, pdf_brdf) : 1.0f;
  const glm::vec3 contribution = f * ls.radiance * (wi.z * w / ls.pdf);
  float keep = 1.0f;
  if (const float y = luminance(contribution); y < weak) {
    keep = y / weak;
    if (!(rng.next_float() < keep)) return glm::vec3(0.0f);
  }
  const Ray shadow = shadow_ray_to(si.position, ng, ls.position, ls.normal);
  ++c->rays;
  if (scene_.accelerator().occluded(shadow)) return glm::vec3(0.0f);
  return contribution / keep;
}

}  // namespace phyir::render
