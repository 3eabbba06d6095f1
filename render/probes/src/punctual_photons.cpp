#include "punctual_photons.h"

#include <algorithm>
#include <cmath>

#include "phyir/core/safe_math.h"
#include "phyir/render/brdf.h"
#include "phyir/render/direct_lighting.h"
#include "phyir/render/equirect.h"
#include "phyir/render/frame.h"
#include "phyir/render/ray_offset.h"
#include "phyir/render/streams.h"
#include "punctual_deposit.h"

namespace phyir::render {

namespace {

// In the balance heuristic's weights a photon counts for 1/kPhotonsPerDirection of one of a
// texel's directions: how many land in a texel's footprint moves with their jitter, so a
// few per texel are far noisier than a few directions (measured on the suite: taking the
// light outright wherever 4 landed per texel, the photons took the lit room's error from
// 0.064 to 0.098). Below
// kMinPhotonsPerTexel the directions take a hit's light alone: the photons' share would be
// small, and joining each probe to every photon it sees would cost a shadow ray each.
constexpr float kPhotonsPerDirection = 16.0f;
constexpr float kMinPhotonsPerTexel = 16.0f;
// Where more land in a texel, about this many are joined to the probe (systematic sampling,
// gather()): next to a bulb tens of thousands would, each a shadow ray.
constexpr float kPhotonsKeptPerTexel = 16.0f;

// A unit direction from the unit square: uniform over the sphere, or over the cap of
// directions within the angle whose cosine is cos_outer of `axis` (equal-area maps, so a
// stratified square stays stratified in solid angle).
glm::vec3 cap_direction(const glm::vec2& u, const glm::vec3& axis, float cos_outer) {
  const float cos_theta = 1.0f - u.x * (1.0f - cos_outer);
  const float sin_theta = std::sqrt(std::max(0.0f, 1.0f - cos_theta * cos_theta));
  const float phi = kTwoPi * u.y;
  const Frame frame(axis);
  return frame.to_world(glm::vec3(sin_theta * std::cos(phi), sin_theta * std::sin(phi), cos_theta));
}

}  // namespace

PunctualPhotons::PunctualPhotons(const RenderScene& scene, int per_light, int spp, uint64_t seed, uint64_t* rays)
    : scene_(&scene), spp_(float(std::max(spp, 1))) {
  const DeltaLights& lights = scene.emitters().delta_lights();
  if (per_light <= 0 || lights.size() > kMaxLights) return;
  const int side = std::max(1, int(std::lround(std::sqrt(double(per_light)))));
  const int count = side * side;
  for (int i = 0; i < lights.size(); ++i) {
    const scenes::PunctualLight& light = lights.light(i);
    if (light.type == scenes::PunctualLight::Type::Directional) continue;
    Source s;
    s.light = i;
    s.position = light.position;
    s.axis = light.type == scenes::PunctualLight::Type::Spot ? glm::normalize(light.direction) : glm::vec3(0, 0, 1);
    s.cos_outer = light.type == scenes::PunctualLight::Type::Spot ? std::cos(light.outer_cone_angle) : -1.0f;
    s.photons_per_steradian = float(count) / (kTwoPi * (1.0f - s.cos_outer));
    const int source = int(sources_.size());
    sources_.push_back(s);
    // A jittered grid over the square, its jitter from the view's seed.
    Rng rng = item_stream(seed, uint64_t(i), Purpose::kProbePhoton);
    for (int a = 0; a < side; ++a) {
      for (int b = 0; b < side; ++b) {
        const glm::vec2 jitter = rng.next_2d();
        const glm::vec2 u((float(a) + jitter.x) / float(side), (float(b) + jitter.y) / float(side));
        const Ray ray{s.position, cap_direction(glm::min(u, glm::vec2(kOneMinusEpsilon)), s.axis, s.cos_outer)};
        Photon p;
        ++*rays;
        if (!scene.trace(ray, &p.hit) || p.hit.transmission > 0.0f) continue;  // glass: path traced
        DeltaIllumination seen;
        if (!lights.illuminate(i, p.hit.position, &seen)) continue;
        p.source = source;
        p.to_light = seen.wi;
        p.irradiance = seen.irradiance;
        photons_.push_back(p);
      }
    }
  }
}

float PunctualPhotons::photons_per_steradian(const Source& s, const glm::vec3& origin, const glm::vec3& position,
                                             const glm::vec3& ng) const {
  const glm::vec3 to_light = s.position - position, to_origin = origin - position;
  const float r2 = glm::dot(to_light, to_light), d2 = glm::dot(to_origin, to_origin);
  if (!(r2 > 0.0f) || !(d2 > 0.0f)) return 0.0f;
  const float r = std::sqrt(r2), d = std::sqrt(d2);
  if (glm::dot(s.axis, -to_light / r) < s.cos_outer) return 0.0f;  // outside a spot's cone
  const float cos_light = std::abs(glm::dot(ng, to_light)) / r;
  const float cos_origin = std::abs(glm::dot(ng, to_origin)) / d;
  // Per unit area of the surface: photons per steradian x cos / r^2; seen from the origin,
  // per steradian there: x d^2 / cos.
  const float value = s.photons_per_steradian * cos_light / r2 * d2 / std::max(cos_origin, 1e-6f);
  return std::isfinite(value) ? value : 0.0f;
}

float PunctualPhotons::share(float photons_per_texel) const {
  const float directions = kPhotonsPerDirection * spp_;
  return photons_per_texel >= kMinPhotonsPerTexel ? photons_per_texel / (directions + photons_per_texel) : 0.0f;
}

bool PunctualPhotons::shares(const glm::vec3& origin, const glm::vec3& position, const glm::vec3& ng,
                             float texel_solid_angle, float* shares) const {
  std::fill(shares, shares + kMaxLights, 0.0f);
  bool any = false;
  for (const Source& s : sources_) {
    shares[s.light] = share(photons_per_steradian(s, origin, position, ng) * texel_solid_angle);
    any = any || shares[s.light] > 0.0f;
  }
  return any;
}

void PunctualPhotons::gather(const glm::vec3& origin, const glm::vec3& normal, int height, int width, uint64_t key,
                             std::vector<glm::vec3>* radiance, std::vector<glm::vec3>* radiance_cos,
                             uint64_t* rays) const {
  const size_t texels = size_t(height * width);
  radiance->assign(texels, glm::vec3(0.0f));
  radiance_cos->assign(texels, glm::vec3(0.0f));
  // The photons this probe takes, each with what it adds if nothing hides it, and their sum
  // per texel (luminance).
  struct Candidate {
    uint32_t photon, texel;
    glm::vec3 value;
  };
  thread_local std::vector<Candidate> candidates;
  thread_local std::vector<float> total, start, reached;
  candidates.clear();
  total.assign(texels, 0.0f);
  for (size_t j = 0; j < photons_.size(); ++j) {
    uint32_t t = 0;
    const glm::vec3 value = unoccluded(photons_[j], origin, height, width, &t);
    if (!(luminance(value) > 0.0f)) continue;
    candidates.push_back({uint32_t(j), t, value});
    total[t] += luminance(value);
  }
  // Systematic sampling in proportion to the values: a texel's candidates laid end to end,
  // each as long as kPhotonsKeptPerTexel x its share of the texel's total, and cut at the
  // integers shifted by u (uniform per texel). A photon is cut `hits` times, on average its
  // length: each cut stands for total / kPhotonsKeptPerTexel of the texel, so the texel's
  // value is exact where nothing hides the photons, and needs about kPhotonsKeptPerTexel
  // shadow rays however many photons land in it.
  start.resize(texels);
  reached.assign(texels, 0.0f);
  Rng rng = generator(key, Purpose::kProbePhotonRoulette);
  for (float& u : start) u = rng.next_float();
  for (const Candidate& c : candidates) {
    const float share = kPhotonsKeptPerTexel * luminance(c.value) / total[c.texel];
    const float before = reached[c.texel];
    reached[c.texel] += share;
    const float hits = std::floor(start[c.texel] + reached[c.texel]) - std::floor(start[c.texel] + before);
    if (!(hits > 0.0f) || !visible(photons_[c.photon], origin, rays)) continue;
    const glm::vec3 value = c.value * (hits / share);
    (*radiance)[c.texel] += value;
    const glm::vec3 d = glm::normalize(photons_[c.photon].hit.position - origin);
    (*radiance_cos)[c.texel] += value * std::max(0.0f, glm::dot(d, normal));
  }
}

glm::vec3 PunctualPhotons::unoccluded(const Photon& p, const glm::vec3& origin, int height, int width,
                                      uint32_t* texel_index) const {
  const SurfaceInteraction& hit = p.hit;
  const glm::vec3 to_origin = origin - hit.position;
  const float d = std::sqrt(glm::dot(to_origin, to_origin));
  if (!(d > 0.0f)) return glm::vec3(0.0f);
  const glm::vec3 wo = to_origin / d;
  if (!(glm::dot(hit.geometric_normal, wo) > 0.0f)) return glm::vec3(0.0f);  // the probe sees the other side
  const glm::ivec2 texel = probe_texel_of(-wo, height, width);
  const float per_texel = photons_per_steradian(sources_[size_t(p.source)], origin, hit.position, hit.geometric_normal) *
                          equirect_texel_solid_angle(texel.x, width, height);
  const float taken = share(per_texel);
  if (!(taken > 0.0f)) return glm::vec3(0.0f);  // the texel's directions take it all
  // What the texel's directions would have added there (TexelEstimator's punctual_light:
  // f_d E cos, at a hit that faces the viewer and the light). Diffuse light only: a glossy
  // highlight is a small spot that a few photons find by chance, as the directions do.
  const ShadingPoint x = shading_point(hit, wo);
  if (!(x.wo.z >= kMinCosine)) return glm::vec3(0.0f);
  const BrdfParams brdf = clamped(hit.brdf);
  const glm::vec3 wi = x.frame.to_local(p.to_light);
  if (!(wi.z >= kMinCosine)) return glm::vec3(0.0f);
  // Each photon stands for 1 / (their density in the probe's solid angle) of it, the
  // texel's radiance is that integral over its solid angle, and the photons' share of it
  // is `taken`.
  const glm::vec3 value = Fd_Lambert(brdf.base_color, brdf.metalness) * p.irradiance * (wi.z * taken / per_texel);
  *texel_index = uint32_t(texel.x * width + texel.y);
  return is_finite(value) ? value : glm::vec3(0.0f);
}

bool PunctualPhotons::visible(const Photon& p, const glm::vec3& origin, uint64_t* rays) const {
  const glm::vec3 wo = glm::normalize(origin - p.hit.position);
  Ray shadow{spawn_origin(p.hit.position, p.hit.geometric_normal, wo), wo};
  shadow.tmax = glm::length(origin - shadow.origin) * (1.0f - kShadowRayShortening);
  ++*rays;
  return !scene_->accelerator().occluded(shadow);
}

}  // namespace phyir::render
