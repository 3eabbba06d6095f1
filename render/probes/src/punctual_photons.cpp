#include "punctual_photons.h"

#include <algorithm>
#include <cmath>

#include "phyir/core/safe_math.h"
#include "phyir/render/brdf.h"
#include "phyir/render/direct_lighting.h"
#include "phyir/render/equirect.h"
#include "phyir/render/frame.h"
#include "phyir/render/ray_offset.h"
#include "phyir/render/sampling.h"
#include "phyir/render/streams.h"
#include "punctual_deposit.h"

namespace phyir::render {

namespace {

// A photon weighs 1/kPhotonsPerDirection of a direction: how many land in a texel moves with
// their jitter, so a few are far noisier than a few directions. Below kMinPhotonsPerTexel the
// directions take the light alone: a small share, at a shadow ray per photon.
constexpr float kPhotonsPerDirection = 16.0f;
constexpr float kMinPhotonsPerTexel = 16.0f;
// About this many joined per texel (gather()): next to a bulb tens of thousands land, each a shadow ray.
constexpr float kPhotonsKeptPerTexel = 16.0f;
// The sun's photons land within this of the probes' surfaces (which bound region_).
constexpr float kRegionMargin = 0.01f;
// The sun's beam in kBeamCells^2 cells; photons go where a cell's kPilotsPerCell^2 pilots got in.
constexpr int kBeamCells = 128;
constexpr int kPilotsPerCell = 2;
// As many as 16 bulbs send: every probe considers every photon, and a wide region wants millions.
constexpr double kMaxSunPhotons = double(1 << 16);

}  // namespace

PunctualPhotons::PunctualPhotons(const RenderScene& scene, int per_light, int spp, const scenes::Bounds& region,
                                 uint64_t seed, uint64_t* rays)
    : scene_(&scene), region_(region), spp_(float(std::max(spp, 1))) {
  const DeltaLights& lights = scene.emitters().delta_lights();
  if (per_light <= 0 || lights.size() > kMaxLights) return;
  for (int i = 0; i < lights.size(); ++i) {
    if (lights.light(i).type == scenes::PunctualLight::Type::Directional)
      trace_from_sun(i, per_light, seed, rays);
    else
      trace_from_light(i, per_light, seed, rays);
  }
}

void PunctualPhotons::trace_from_light(int i, int per_light, uint64_t seed, uint64_t* rays) {
  const scenes::PunctualLight& light = scene_->emitters().delta_lights().light(i);
  const int side = std::max(1, int(std::lround(std::sqrt(double(per_light)))));
  Source s;
  s.light = i;
  s.position = light.position;
  s.axis = light.type == scenes::PunctualLight::Type::Spot ? glm::normalize(light.direction) : glm::vec3(0, 0, 1);
  s.cos_outer = light.type == scenes::PunctualLight::Type::Spot ? std::cos(light.outer_cone_angle) : -1.0f;
  s.density = float(side * side) * uniform_cone_pdf(1.0f, s.cos_outer);
  const int source = int(sources_.size());
  sources_.push_back(s);
  // A jittered grid over the square, its jitter from the view's seed.
  Rng rng = item_stream(seed, uint64_t(i), Purpose::kProbePhoton);
  const Frame around(s.axis);
  for (int a = 0; a < side; ++a) {
    for (int b = 0; b < side; ++b) {
      const glm::vec2 jitter = rng.next_2d();
      const glm::vec2 u((float(a) + jitter.x) / float(side), (float(b) + jitter.y) / float(side));
      const glm::vec3 local = sample_uniform_cone(glm::min(u, glm::vec2(kOneMinusEpsilon)), s.cos_outer);
      trace_photon(Ray{s.position, around.to_world(local)}, source, rays);
    }
  }
}

void PunctualPhotons::trace_from_sun(int i, int per_square_metre, uint64_t seed, uint64_t* rays) {
  if (region_.empty()) return;
  Source s;
  s.light = i;
  s.directional = true;
  s.axis = glm::normalize(scene_->emitters().delta_lights().light(i).direction);
  // A square across the beam, as wide as the region's bounding sphere, upstream of everything.
  Beam& beam = s.beam;
  beam.centre = 0.5f * (region_.min + region_.max);
  beam.half_width = 0.5f * glm::length(region_.max - region_.min) + kRegionMargin;
  const scenes::Bounds& all = scene_->scene().bounds;
  beam.upstream = glm::length(glm::max(glm::abs(all.min - beam.centre), glm::abs(all.max - beam.centre))) +
                  beam.half_width + 1.0f;
  const Frame across(s.axis);
  beam.t = across.t, beam.b = across.b;
  beam.density.assign(size_t(kBeamCells * kBeamCells), 0.0f);
  const int source = int(sources_.size());
  sources_.push_back(s);
  Rng rng = item_stream(seed, uint64_t(i), Purpose::kProbePhoton);
  const std::vector<int> cells = cells_reaching_region(sources_.back(), &rng, rays);
  if (cells.empty()) return;
  const float cell_width = 2.0f * beam.half_width / float(kBeamCells), cell_area = cell_width * cell_width;
  const double per_cell = std::min(double(per_square_metre) * cell_area, double(kMaxSunPhotons) / double(cells.size()));
  const int side = std::max(1, int(std::floor(std::sqrt(per_cell))));
  for (int c : cells) {
    sources_[size_t(source)].beam.density[size_t(c)] = float(side * side) / cell_area;
    for (int a = 0; a < side; ++a)
      for (int b = 0; b < side; ++b) {
        const glm::vec2 u = (glm::vec2(float(a), float(b)) + rng.next_2d()) / float(side);
        trace_photon(sources_[size_t(source)].beam.ray(c, u, s.axis), source, rays);
      }
  }
}

std::vector<int> PunctualPhotons::cells_reaching_region(const Source& s, Rng* rng, uint64_t* rays) const {
  // Pilots in region_ mark their cell, grown by one (a window's edge can fall between pilots).
  std::vector<char> reached(s.beam.density.size(), 0);
  for (int c = 0; c < kBeamCells * kBeamCells; ++c)
    for (int a = 0; a < kPilotsPerCell; ++a)
      for (int b = 0; b < kPilotsPerCell; ++b) {
        const glm::vec2 u = (glm::vec2(float(a), float(b)) + rng->next_2d()) / float(kPilotsPerCell);
        SurfaceInteraction hit;
        ++*rays;
        if (scene_->trace(s.beam.ray(c, u, s.axis), &hit) && in_region(hit.position)) reached[size_t(c)] = 1;
      }
  auto reached_at = [&](int x, int y) {
    return x >= 0 && y >= 0 && x < kBeamCells && y < kBeamCells && reached[size_t(y * kBeamCells + x)];
  };
  std::vector<int> cells;
  for (int y = 0; y < kBeamCells; ++y)
    for (int x = 0; x < kBeamCells; ++x) {
      bool near = false;
      for (int dy = -1; dy <= 1; ++dy)
        for (int dx = -1; dx <= 1; ++dx) near = near || reached_at(x + dx, y + dy);
      if (near) cells.push_back(y * kBeamCells + x);
    }
  return cells;
}

Ray PunctualPhotons::Beam::ray(int cell, const glm::vec2& u, const glm::vec3& axis) const {
  const glm::vec2 at = (glm::vec2(float(cell % kBeamCells), float(cell / kBeamCells)) + u) / float(kBeamCells);
  const glm::vec2 square = (2.0f * at - 1.0f) * half_width;
  return Ray{centre + square.x * t + square.y * b - upstream * axis, axis};
}

int PunctualPhotons::Beam::cell_of(const glm::vec3& p) const {
  const glm::vec3 q = p - centre;
  const glm::vec2 at = (glm::vec2(glm::dot(q, t), glm::dot(q, b)) / half_width + 1.0f) * 0.5f * float(kBeamCells);
  if (!(at.x >= 0.0f && at.y >= 0.0f && at.x < float(kBeamCells) && at.y < float(kBeamCells))) return -1;
  return int(at.y) * kBeamCells + int(at.x);
}

void PunctualPhotons::trace_photon(const Ray& ray, int source, uint64_t* rays) {
  const Source& s = sources_[size_t(source)];
  Photon p;
  ++*rays;
  if (!scene_->trace(ray, &p.hit) || p.hit.transmission > 0.0f) return;  // glass: path traced
  if (s.directional && !in_region(p.hit.position)) return;
  DeltaIllumination seen;
  if (!scene_->emitters().delta_lights().illuminate(s.light, p.hit.position, &seen)) return;
  p.source = source;
  p.to_light = seen.wi;
  p.irradiance = seen.irradiance;
  photons_.push_back(p);
}

bool PunctualPhotons::in_region(const glm::vec3& p) const {
  return glm::all(glm::greaterThanEqual(p, region_.min - kRegionMargin)) &&
         glm::all(glm::lessThanEqual(p, region_.max + kRegionMargin));
}

float PunctualPhotons::photons_per_steradian(const Source& s, const glm::vec3& origin, const glm::vec3& position,
                                             const glm::vec3& ng) const {
  const glm::vec3 to_origin = origin - position;
  const float d2 = glm::dot(to_origin, to_origin);
  if (!(d2 > 0.0f)) return 0.0f;
  // Per unit area of the surface: per unit area facing the light x cos there.
  float per_area = 0.0f;
  if (s.directional) {
    const int cell = s.beam.cell_of(position);
    if (cell < 0 || !in_region(position)) return 0.0f;
    per_area = s.beam.density[size_t(cell)] * std::abs(glm::dot(ng, s.axis));
  } else {
    const glm::vec3 to_light = s.position - position;
    const float r2 = glm::dot(to_light, to_light);
    if (!(r2 > 0.0f)) return 0.0f;
    const float r = std::sqrt(r2);
    if (glm::dot(s.axis, -to_light / r) < s.cos_outer) return 0.0f;  // outside a spot's cone
    per_area = s.density / r2 * std::abs(glm::dot(ng, to_light)) / r;
  }
  // Seen from the origin, per steradian there: x d^2 / cos.
  const float cos_origin = std::abs(glm::dot(ng, to_origin)) / std::sqrt(d2);
  const float value = per_area * d2 / std::max(cos_origin, 1e-6f);
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
                             uint64_t* rays, const std::vector<float>* scale) const {
  const size_t texels = size_t(height * width);
  radiance->assign(texels, glm::vec3(0.0f));
  radiance_cos->assign(texels, glm::vec3(0.0f));
  // The photons this probe takes, with what each adds unhidden, and their luminance per texel.
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
    const glm::vec3 value = unoccluded(photons_[j], origin, height, width, scale, &t);
    if (!(luminance(value) > 0.0f)) continue;
    candidates.push_back({uint32_t(j), t, value});
    total[t] += luminance(value);
  }
  // Systematic sampling by value, kPhotonsKeptPerTexel cuts per texel at integers shifted by u:
  // each cut stands for total / kPhotonsKeptPerTexel, exact where nothing hides the photons.
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
                                      const std::vector<float>* scale, uint32_t* texel_index) const {
  const SurfaceInteraction& hit = p.hit;
  const glm::vec3 to_origin = origin - hit.position;
  const float d = std::sqrt(glm::dot(to_origin, to_origin));
  if (!(d > 0.0f)) return glm::vec3(0.0f);
  const glm::vec3 wo = to_origin / d;
  if (!(glm::dot(hit.geometric_normal, wo) > 0.0f)) return glm::vec3(0.0f);  // the probe sees the other side
  const glm::ivec2 texel = probe_texel_of(-wo, height, width);
  // A texel outside the pass being shaded (scale 0) is skipped before its density is worked out.
  const float counted = scale ? (*scale)[size_t(texel.x * width + texel.y)] : 1.0f;
  if (!(counted > 0.0f)) return glm::vec3(0.0f);
  const float per_texel = photons_per_steradian(sources_[size_t(p.source)], origin, hit.position, hit.geometric_normal) *
                          equirect_texel_solid_angle(texel.x, width, height);
  const float taken = share(per_texel * counted);
  if (!(taken > 0.0f)) return glm::vec3(0.0f);  // the texel's directions take it all
  // What the texel's directions would add there (TexelEstimator's punctual_light: f_d E cos,
  // facing viewer and light). Diffuse only: photons find a glossy highlight by chance too.
  const ShadingPoint x = shading_point(hit, wo);
  if (!(x.wo.z >= kMinCosine)) return glm::vec3(0.0f);
  const BrdfParams brdf = clamped(hit.brdf);
  const glm::vec3 wi = x.frame.to_local(p.to_light);
  if (!(wi.z >= kMinCosine)) return glm::vec3(0.0f);
  // Each photon is 1 / per_texel of the texel's mean radiance; the photons take `taken` of it.
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
