#include "probe_texel_estimator.h"

#include <algorithm>
#include <cmath>

#include "phyir/core/safe_math.h"
#include "phyir/render/ray_offset.h"
#include "phyir/render/streams.h"

namespace phyir::render {

namespace {

// A BRDF-sampled ray's hit is followed with probability min(1, kSpecularKeepScale x the
// specular share of its weight), weighted by the inverse: a glossy or metal lobe always, a
// pale wall's in about a quarter of the samples, none in fewer than 1/8 (no weight over 8).
constexpr float kSpecularKeepScale = 4.0f;
constexpr float kMinSpecularKeep = 0.125f;

// Light samples at a probe ray's own hit near a light, where a thin or nearby emitter's light
// varies most (docs/probes-estimator.md, step 4); scaled by albedo where the hit emits.
constexpr int kNearLightSamples = 8;

// Punctual lights evaluated exactly at each hit (one shadow ray each) in scenes of up to this
// many; beyond, the cost per direction would grow with them, and the cache's value is used.
constexpr int kMaxExactPunctualLights = 8;

// A specular next-event sample adding less than this fraction of the diffuse light traces
// its shadow ray with probability share / this (docs/probes-estimator.md, step 3: 23% fewer
// rays for 1% more error).
constexpr float kWeakShadowFraction = 0.05f;

}  // namespace

void TexelEstimator::CacheTrace::note(const glm::vec3& lobe, const CachedIrradiance& E, bool with_direct) const {
  if (!notes || E.block == 0 || notes->cache_reads >= SampleNotes::kMaxCacheReads) return;
  // E's luminance variance scaled by what the path carries of E's colour.
  const glm::vec3 used = with_direct ? E.indirect + E.direct : E.indirect;
  const float variance = E.indirect_variance + (with_direct ? E.direct_variance : 0.0f);
  const float scale = safe_div(luminance(throughput * lobe * used), luminance(used));
  notes->cache[size_t(notes->cache_reads++)] = {E.block, scale * std::sqrt(std::max(variance, 0.0f))};
}

CachePoint cache_point(const SurfaceInteraction& si, const glm::vec3& shading_normal) {
  return CachePoint{si.position, shading_normal, si.geometric_normal};
}

TexelEstimator::TexelEstimator(const RenderScene& scene, const Effects& effects, const ProbeSettings& settings,
                               const RadianceCache* cache, const PunctualPhotons* photons)
    : scene_(scene),
      settings_(settings),
      cache_(cache),
      tracer_(scene, effects, settings.path),
      exact_punctual_(scene.emitters().delta_lights().size() <= kMaxExactPunctualLights),
      // The photons stand in for exact punctual light only (punctual_at's, near_light's).
      photons_(photons && !photons->empty() && exact_punctual_ ? photons : nullptr) {}

glm::vec3 TexelEstimator::sample(const Ray& ray, uint64_t key, Part part, const FootCorrection& foot,
                                 float texel_solid_angle, SampleNotes* notes, PathCounters* c) const {
  if (settings_.mode == ProbeMode::kPath) return tracer_.radiance(ray, key, c);
  if (part == Part::kEmission) {  // most of these rays: a light texel's many directions
    glm::vec3 Le;
    float t = 0.0f;
    ++c->rays;
    if (!scene_.trace_emission(ray, &Le, &t)) return miss(ray.direction);
    notes->distance = t;
    notes->emitted = Le;
    return Le;
  }
  SurfaceInteraction si;
  ++c->rays;
  if (!scene_.trace(ray, &si)) {
    if (part == Part::kRest) return glm::vec3(0.0f);
    // The environment is a light: its window frames and horizons are edges to supersample.
    const glm::vec3 sky = miss(ray.direction);
    if (max_component(sky) > 0.0f) notes->seen |= kSeenHard | kSeenSky;
    return sky;
  }
  notes->distance = si.distance;
  const glm::vec3 Le = si.emits ? si.emission : glm::vec3(0.0f);
  // Hard to sample: a light (unless estimated apart), glass, a glossy surface's highlights.
  if ((si.emits && part == Part::kAll) || si.transmission > 0.0f || si.brdf.roughness < settings_.glossy_roughness)
    notes->seen |= kSeenHard;
  const glm::vec3 L = part == Part::kAll ? Le : glm::vec3(0.0f);
  notes->emitted = L;
  if (settings_.path.max_bounces < 1) return L;
  if (si.transmission > 0.0f)  // glass: path traced from its hit
    return L + tracer_.continue_from(si, ray, key, settings_.path.max_bounces, c);
  FirstHit first;
  first.foot = &foot;
  float shares[PunctualPhotons::kMaxLights];
  if (photons_ && photons_->shares(ray.origin, si.position, si.geometric_normal, texel_solid_angle, shares))
    first.photon_shares = shares;
  return L + reflected(si, -ray.direction, 0, key, c, CacheTrace{notes}, &first);
}

glm::vec3 TexelEstimator::miss(const glm::vec3& direction) const {
  return scene_.environment() ? scene_.environment()->radiance(direction) : glm::vec3(0.0f);
}

glm::vec3 TexelEstimator::reflected(const SurfaceInteraction& si, const glm::vec3& wo_world, int depth, uint64_t key,
                                    PathCounters* c, const CacheTrace& trace, const FirstHit* first) const {
  ShadingPoint x = shading_point(si, wo_world);
  if (!(x.wo.z >= kMinCosine)) return glm::vec3(0.0f);
  x.brdf = clamped(si.brdf);
  const BrdfParams& p = x.brdf;
  const glm::vec3 fd = Fd_Lambert(p.base_color, p.metalness);
  CachedIrradiance E = lookup(si, x, depth, key, c);
  const float* photon_shares = first ? first->photon_shares : nullptr;
  if (first && first->foot) first->foot->apply(si.position, x.frame.n, &E);
  const bool split = E.has_direct && !is_mirror(p.roughness);
  trace.note(fd, E, split);
  if (split) return reflected_split(x, fd, E, depth, key, c, photon_shares, trace);
  glm::vec3 L(0.0f);
  if (max_component(fd) > 0.0f) L += fd * E.indirect;

  // Several light samples at a probe ray's own hit (near a light, most of the noise), one deeper.
  DirectLightOptions nee;
  nee.light_samples = depth == 0 ? near_light_samples(si, x) : 1;
  L += near_light(x, &nee, depth, key, c, photon_shares);

  // reflected_split()'s control variate on every rough surface (the roulette below depends on
  // the sample, so it cannot be the condition).
  const int next = depth + 1;
  const bool controlled = next < settings_.path.max_bounces && p.roughness >= settings_.glossy_roughness;
  const glm::vec3 uniform = controlled ? E.indirect * kInvPi : glm::vec3(0.0f);
  if (controlled) L += specular_albedo(p, x.wo.z) * uniform;

  Rng rng = stream(key, Purpose::kTexelBrdf, uint64_t(depth));
  const float u_lobe = rng.next_float();
  BrdfSample bs;
  if (!brdf_sample(p, x.wo, u_lobe, rng.next_2d(), &bs)) return L;
  const glm::vec3 wi_world = x.frame.to_world(bs.wi);
  if (glm::dot(wi_world, x.geometric_normal) <= 0.0f) return L;  // leaks below the surface: dropped, as the integrator does
  // The specular lobe's part of the weight (the diffuse part is the cache's).
  const glm::vec3 weight_specular = bs.delta ? bs.weight : specular_eval(p, x.wo, bs.wi) * safe_div(bs.wi.z, bs.pdf);
  const Ray ray{spawn_origin(si.position, x.geometric_normal, wi_world), wi_world};
  SurfaceInteraction y;
  ++c->rays;
  if (!scene_.trace(ray, &y)) return L + weight_specular * (miss(wi_world) - uniform);  // the diffuse share is in E
  if (y.emits) {
    const bool weighted = has_lights(scene_) && !bs.delta;
    L += bs.weight * y.emission * (weighted ? emitter_hit_weight(scene_, si.position, bs.pdf, y, nee.light_samples, nee.punctual) : 1.0f);
  }
  if (next >= settings_.path.max_bounces || !(max_component(weight_specular) > 0.0f)) return L;
  const float share = safe_div(luminance(weight_specular), luminance(bs.weight));
  const float keep = std::clamp(kSpecularKeepScale * share, kMinSpecularKeep, 1.0f);
  if (keep < 1.0f && !(stream(key, Purpose::kTexelSpecularRoulette, uint64_t(depth)).next_float() < keep)) return L;
  const CacheTrace after = trace.after(weight_specular / keep);
  return L + weight_specular * (reflected_at(ray, y, next, depth, key, c, glossy(p), after) - uniform) / keep;
}

CachedIrradiance TexelEstimator::lookup(const SurfaceInteraction& si, const ShadingPoint& x, int depth, uint64_t key,
                                        PathCounters* c) const {
  return cache_->lookup(cache_point(si, x.frame.n), stream_key(key, Purpose::kTexelLookup, uint64_t(depth)), c);
}

glm::vec3 TexelEstimator::reflected_at(const Ray& ray, const SurfaceInteraction& y, int next, int depth, uint64_t key,
                                       PathCounters* c, bool from_glossy, const CacheTrace& trace) const {
  // The bounces a path traced from y may take.
  const int budget = std::max(settings_.path.max_bounces - std::min(next, kMaxSpecularDepth), 0);
  if (y.transmission > 0.0f)  // glass: the path tracer from here
    return tracer_.continue_from(y, ray, stream_key(key, Purpose::kTexelGlass, uint64_t(depth)), budget, c);
  if (from_glossy && y.brdf.roughness < settings_.glossy_roughness && next < kMaxSpecularDepth)
    return reflected(y, -ray.direction, next, key, c, trace);
  // The chain's end: the cache's uniformly lit lobe, or on a glossy y with probability
  // chain_end_paths (progressive passes) the path tracer's light, for the sharp images the
  // uniform lobe misses; a rough y's lobe is nearly uniform, not worth a path.
  if (settings_.chain_end_paths > 0.0f && glossy(y.brdf) &&
      stream(key, Purpose::kTexelChainEnd, uint64_t(depth)).next_float() < settings_.chain_end_paths)
    return tracer_.continue_from(y, ray, stream_key(key, Purpose::kTexelChainEndPath, uint64_t(depth)), budget, c);
  return terminal(y, -ray.direction, next, key, c, trace);
}

glm::vec3 TexelEstimator::reflected_split(const ShadingPoint& x, const glm::vec3& fd, const CachedIrradiance& E,
                                          int depth, uint64_t key, PathCounters* c, const float* photon_shares,
                                          const CacheTrace& trace) const {
  const BrdfParams& p = x.brdf;
  glm::vec3 L = fd * (E.indirect + E.direct + punctual_at(x, E, c, photon_shares));
  const glm::vec3 albedo = specular_albedo(p, x.wo.z);
  const float albedo_s = luminance(albedo);
  const float share = safe_div(albedo_s, albedo_s + kPi * luminance(fd));
  if (!(share > 0.0f)) return L;
  const float keep = std::clamp(kSpecularKeepScale * share, kMinSpecularKeep, 1.0f);
  const bool emitters = has_lights(scene_);
  // Shadow ray rouletted where the sample adds little to the diffuse light (kWeakShadowFraction).
  DirectLightOptions nee;
  nee.lobes = Lobes::kSpecular;
  nee.brdf_strategy_probability = keep;
  nee.weak = kWeakShadowFraction * luminance(L);
  if (emitters) L += direct_light(x, nee, depth, key, c);
  const int next = depth + 1;
  // Control variate (rouletted rays only): the lobe under uniform light E.indirect / pi is
  // exact; the ray estimates only the difference, so a skipped ray costs far less.
  const glm::vec3 uniform = (keep < 1.0f && next < settings_.path.max_bounces) ? E.indirect * kInvPi : glm::vec3(0.0f);
  L += albedo * uniform;
  if (keep < 1.0f && !(stream(key, Purpose::kTexelSpecularRoulette, uint64_t(depth)).next_float() < keep)) return L;

  Rng rng = stream(key, Purpose::kTexelBrdf, uint64_t(depth));
  glm::vec3 wi;
  float pdf;
  if (!specular_sample(p, x.wo, rng.next_2d(), &wi, &pdf)) return L;
  pdf *= keep;  // the ray's effective density
  const glm::vec3 wi_world = x.frame.to_world(wi);
  if (!(glm::dot(wi_world, x.geometric_normal) > 0.0f)) return L;
  const glm::vec3 weight = specular_eval(p, x.wo, wi) * safe_div(wi.z, pdf);
  if (!(max_component(weight) > 0.0f)) return L;
  const Ray ray{spawn_origin(x.position, x.geometric_normal, wi_world), wi_world};
  SurfaceInteraction y;
  ++c->rays;
  if (!scene_.trace(ray, &y)) return L + weight * (miss(wi_world) - uniform);
  if (y.emits) L += weight * y.emission * (emitters ? emitter_hit_weight(scene_, x.position, pdf, y) : 1.0f);
  if (next < settings_.path.max_bounces)
    L += weight * (reflected_at(ray, y, next, depth, key, c, glossy(p), trace.after(weight)) - uniform);
  return L;
}

glm::vec3 TexelEstimator::terminal(const SurfaceInteraction& si, const glm::vec3& wo_world, int depth, uint64_t key,
                                   PathCounters* c, const CacheTrace& trace) const {
  ShadingPoint x = shading_point(si, wo_world);
  if (!(x.wo.z >= kMinCosine)) return glm::vec3(0.0f);
  x.brdf = clamped(si.brdf);
  const BrdfParams& p = x.brdf;
  glm::vec3 L(0.0f);
  const glm::vec3 lobe = mean_brdf(p, x.wo.z);
  const CachedIrradiance E = lookup(si, x, depth, key, c);
  trace.note(lobe, E, E.has_direct);
  // The lobe lit uniformly, punctual lights taken at y itself: the cache blurs their hard
  // shadows, which a polished surface reflects sharply.
  if (E.has_direct) return lobe * (E.indirect + E.direct + punctual_at(x, E, c, nullptr));
  // Light sampling alone: no BRDF-sampled ray at a chain's end competes for the emitters.
  DirectLightOptions nee;
  nee.mis = false;
  L += near_light(x, &nee, depth, key, c);
  return L + lobe * E.indirect;
}

int TexelEstimator::near_light_samples(const SurfaceInteraction& si, const ShadingPoint& x) const {
  if (!si.emits) return kNearLightSamples;
  const float albedo = kPi * luminance(mean_brdf(x.brdf, x.wo.z));
  return std::clamp(int(std::ceil(float(kNearLightSamples) * albedo)), 1, kNearLightSamples);
}

glm::vec3 TexelEstimator::punctual_at(const ShadingPoint& x, const CachedIrradiance& E, PathCounters* c,
                                       const float* photon_shares) const {
  if (!exact_punctual_) return E.punctual;
  return punctual_light(scene_, x, Lobes::kCosine, c, photon_shares);
}

glm::vec3 TexelEstimator::near_light(const ShadingPoint& x, DirectLightOptions* nee, int depth, uint64_t key,
                                     PathCounters* c, const float* photon_shares) const {
  if (!has_lights(scene_)) return glm::vec3(0.0f);
  nee->punctual = !exact_punctual_;
  glm::vec3 L = direct_light(x, *nee, depth, key, c);
  if (exact_punctual_) L += punctual_light(scene_, x, Lobes::kAll, c, photon_shares);
  return L;
}

glm::vec3 TexelEstimator::direct_light(const ShadingPoint& x, const DirectLightOptions& options, int depth,
                                       uint64_t key, PathCounters* c) const {
  glm::vec3 sum(0.0f);
  for (int k = 0; k < options.light_samples; ++k) {
    Rng rng = stream(stream_key(key, Purpose::kTexelLightRepeat, uint64_t(k)), Purpose::kTexelLight, uint64_t(depth));
    LightVariates u;
    u.select = rng.next_float();
    u.point = rng.next_2d();
    sum += sample_emitter_light(scene_, x, u, options, glm::vec3(1.0f), &rng, c);
  }
  return sum / float(options.light_samples);
}

}  // namespace phyir::render
