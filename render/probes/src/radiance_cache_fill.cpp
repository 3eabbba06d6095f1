#include "radiance_cache.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "phyir/core/safe_math.h"
#include "phyir/render/direct_lighting.h"
#include "phyir/render/emitter_sampler.h"
#include "phyir/render/frame.h"
#include "phyir/render/probe_grid.h"
#include "phyir/render/ray_offset.h"
#include "phyir/render/streams.h"
#include "phyir/render/sampling.h"

// The radiance cache's fill: a cell's irradiance estimates (docs/probes-estimator.md, "The radiance
// cache": fill and lookup). Discovery, layout, smoothing and lookups: radiance_cache.cpp.

namespace phyir::render {

namespace {

// A cache point as the light estimators see it; irradiance needs no BRDF or viewer.
ShadingPoint shading_point_at(const CachePoint& point) {
  ShadingPoint x;
  x.position = point.position;
  x.geometric_normal = point.geometric_normal;
  x.frame = Frame(point.shading_normal);
  return x;
}

// Stores a finite indirect estimate E in *out (counts a non-finite one) and returns *out.
CachedIrradiance finish_indirect(const glm::vec3& E, CachedIrradiance* out, PathCounters* counters) {
  if (is_finite(E)) out->indirect = E;
  else ++counters->nonfinite_samples;
  return *out;
}

// The variance of a cell's mean luminance by batch means: each point's samples are stratified
// apart, so its mean is an independent estimate of variance c / n_k; their weighted spread,
// sum n_k (mean_k - mean)^2 / (points - 1), estimates c, and the cell's mean has c / N. Unlike
// the samples' own spread it keeps the stratification's gain; what the irradiance varies over
// the cell's few centimetres adds to it. One point: its strata's pair differences
// (stratified_mean_variance), which count the light's variation across a stratum.
class CellVariance {
 public:
  void add(float luminance) { values_.push_back(luminance); }
  void end_point(const std::vector<glm::vec2>& strata) {
    double sum = 0.0;
    for (float y : values_) sum += y;
    if (!values_.empty()) {
      points_.push_back({double(values_.size()), sum / double(values_.size())});
      if (points_.size() == 1) single_ = stratified_mean_variance(strata, values_, 1);
    }
    values_.clear();
  }
  float variance() const {
    if (points_.size() < 2) return float(std::max(single_, 0.0));
    double n = 0.0, weighted = 0.0;
    for (const Point& p : points_) n += p.samples, weighted += p.samples * p.mean;
    const double mean = weighted / n;
    double spread = 0.0;
    for (const Point& p : points_) spread += p.samples * (p.mean - mean) * (p.mean - mean);
    return float(spread / double(points_.size() - 1) / n);
  }

 private:
  struct Point {
    double samples, mean;
  };
  std::vector<float> values_;  // the current point's
  std::vector<Point> points_;
  double single_ = 0.0;  // the first point's stratified variance
};

}  // namespace

void RadianceCache::fill(Cell* cell, PathCounters* counters) const {
  // Direct light only far from every emitter; with no emitters it is 0, unsampled.
  const EmitterSampler& emitters = scene_->emitters();
  float nearest = std::numeric_limits<float>::infinity();
  for (int k = 0; k < cell->count; ++k) nearest = std::min(nearest, emitters.distance_bound(cell->points[k].position));
  cell->has_direct = settings_.direct_distance_cells > 0.0f &&
                     nearest >= settings_.direct_distance_cells * settings_.cell_size;
  const bool sample_direct = cell->has_direct && has_lights(*scene_) && max_bounces_ >= 1;

  // samples_per_cell estimates shared out over the points, each point's stratified.
  const int total = std::max(settings_.samples_per_cell, 1);
  glm::dvec3 indirect(0.0), direct(0.0);
  CellVariance indirect_variance, direct_variance;
  std::vector<glm::vec2> directions, light_points;
  int sample = 0;
  for (int k = 0; k < cell->count; ++k) {
    const int n = total / cell->count + (k < total % cell->count ? 1 : 0);
    const uint64_t point_key = item_stream_key(settings_.seed, cell->key, Purpose::kCachePoint, uint64_t(k));
    Rng permutation = stream(point_key, Purpose::kCacheFillDirections);
    stratified_square(n, permutation, &directions);
    if (sample_direct) {
      Rng light_permutation = stream(point_key, Purpose::kCacheFillLightPoints);
      stratified_square(n, light_permutation, &light_points);
    }
    for (int s = 0; s < n; ++s) {
      const uint64_t key = sample_key(settings_.seed, cell->key, uint64_t(sample++));
      const float u_select = sample_direct ? stream(key, Purpose::kCacheFillLight).next_float() : 0.0f;
      const CachedIrradiance e = estimate(cell->points[k], directions[size_t(s)], sample_direct, u_select,
                                          sample_direct ? light_points[size_t(s)] : glm::vec2(0.0f), key, counters);
      indirect += glm::dvec3(e.indirect);
      direct += glm::dvec3(e.direct);
      indirect_variance.add(luminance(e.indirect));
      direct_variance.add(luminance(e.direct));
    }
    indirect_variance.end_point(directions);
    direct_variance.end_point(sample_direct ? light_points : directions);
  }
  if (sample_direct && !emitters.delta_lights().empty()) {
    glm::vec3 punctual(0.0f);
    for (int k = 0; k < cell->count; ++k)
      punctual += punctual_light(*scene_, shading_point_at(cell->points[k]), Lobes::kCosine, counters);
    cell->punctual = punctual / float(std::max(cell->count, 1));
  }
  const double count = double(std::max(sample, 1));
  cell->indirect = glm::vec3(indirect / count);
  cell->direct = glm::vec3(direct / count);
  cell->indirect_variance = indirect_variance.variance();
  cell->direct_variance = direct_variance.variance();
}

CachedIrradiance RadianceCache::estimate(const CachePoint& point, const glm::vec2& u, bool direct, float u_select,
                                         const glm::vec2& u_light, uint64_t key, PathCounters* counters) const {
  // Indirect: light scattered at least once, plus the environment (also sampled on its own);
  // one cosine direction, cos / pdf = pi. Direct (if asked): one light sample and that
  // direction's emission. Both pairs combined by the power heuristic.
  CachedIrradiance out;
  out.has_direct = direct;
  if (max_bounces_ < 1) return out;  // nothing is reflected at all
  const RenderScene& scene = *scene_;
  const glm::vec3& ng = point.geometric_normal;
  const ShadingPoint x = shading_point_at(point);
  if (direct && has_lights(scene)) {
    DirectLightOptions irradiance;
    irradiance.lobes = Lobes::kCosine;
    irradiance.punctual = false;  // exact in Cell::punctual
    const glm::vec3 E = sample_emitter_light(scene, x, LightVariates{u_select, u_light}, irradiance, glm::vec3(1.0f),
                                             nullptr, counters);
    if (is_finite(E)) out.direct += E;
    else ++counters->nonfinite_samples;
  }
  const EnvironmentLight* environment = scene.environment();
  glm::vec3 E = environment ? environment_irradiance(x, key, counters) : glm::vec3(0.0f);
  // A light subpath, joined here and along the cosine ray's path, weighed against the
  // punctual lights' estimates there (docs/light-subpaths.md).
  const LightSubpaths* subpaths = max_bounces_ >= 2 ? tracer_.light_subpaths() : nullptr;
  LightVertex subpath;
  bool has_subpath = false;
  if (subpaths) {
    Rng rng = stream(key, Purpose::kCacheFillLightSubpath);
    LightSubpathVariates v;
    v.choice = rng.next_float();
    v.direction = rng.next_2d();
    has_subpath = subpaths->sample(point.position, v, &subpath, counters);
    if (has_subpath) E += subpaths->join(x, subpath, Lobes::kCosine, GuideMixture{}, glm::vec3(1.0f), counters);
  }
  const glm::vec3 local = sample_cosine_hemisphere(u);
  const glm::vec3 wi = x.frame.to_world(local);
  if (!(local.z >= kMinCosine) || glm::dot(wi, ng) <= 0.0f) return finish_indirect(E, &out, counters);
  const Ray ray{spawn_origin(point.position, ng, wi), wi};
  SurfaceInteraction si;
  ++counters->rays;
  if (!scene.trace(ray, &si)) {
    // The environment seen by the cosine ray, weighted against its own sample.
    if (environment)
      E += environment->radiance(wi) * (kPi * environment_hit_weight(scene, point.position, local.z * kInvPi, wi));
  } else {
    const glm::vec3 Le = si.emits ? si.emission : glm::vec3(0.0f);
    if (direct && si.emits) {
      const float w = emitter_hit_weight(scene, point.position, local.z * kInvPi, si, 1, false);
      const glm::vec3 D = kPi * Le * w;
      if (is_finite(D)) out.direct += D;
      else ++counters->nonfinite_samples;
    }
    // The light the hit reflects (its emission is direct light, above).
    if (max_bounces_ >= 2)
      E += kPi * tracer_.continue_from(si, ray, PreviousVertex{point.position, local.z * kInvPi, point.position},
                                       has_subpath ? &subpath : nullptr, key, max_bounces_ - 1, counters);
  }
  return finish_indirect(E, &out, counters);
}

glm::vec3 RadianceCache::environment_irradiance(const ShadingPoint& x, uint64_t key, PathCounters* counters) const {
  // The sky through a window is a small bright patch cosine rays rarely find: sample the
  // environment by its own density too (power heuristic; the cosine half is in estimate()).
  Rng rng = stream(key, Purpose::kCacheFillEnvironment);
  const glm::vec3 u(rng.next_float(), rng.next_float(), rng.next_float());
  glm::vec3 u_portal(0.0f);
  if (!scene_->portals().empty()) {
    Rng portal = stream(key, Purpose::kCacheFillPortal);
    const float u_choice = portal.next_float();
    u_portal = glm::vec3(portal.next_2d(), u_choice);
  }
  return sample_environment_light(*scene_, x, u, u_portal, glm::vec3(1.0f), counters, Lobes::kCosine);
}

}  // namespace phyir::render
