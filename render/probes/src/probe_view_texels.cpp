#include "probe_view.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "phyir/core/safe_math.h"
#include "phyir/render/equirect.h"
#include "phyir/render/streams.h"
#include "visible_emission.h"

// ProbeView's texels: first samples, final value, batch estimates and storage
// (docs/probes-estimator.md, "The texel estimator" and "Hard texels"). Passes in probe_view.cpp.

namespace phyir::render {

namespace {
// Deep texels: hard samples spread over kDeepSpreadRatio x (their mean + the floor) found a rare
// bright part; kDeepSppFactor x hard_spp fresh samples then (docs/probes-estimator.md, "Hard texels").
constexpr int kDeepSppFactor = 4;
constexpr float kDeepSpreadRatio = 4.0f;

// A lit texel's emission seen directly, in spp: occlusion rays inside the parts a light covers
// where that is known, else directions over the texel; the Edge ones where an outline crosses it.
// Fewer raise the bench's error (docs/probes-estimator.md, "Lights seen directly: exact coverage").
constexpr int kLightPartSppFactor = 4;
constexpr int kLightPartEdgeSppFactor = 64;
constexpr int kEmissionSppFactor = 16;
constexpr int kEmissionEdgeSppFactor = 256;
// A hard texel that saw the environment: its fresh directions, in spp, at least as many as a
// light's emission seen directly takes (docs/probes-estimator.md, "Hard texels").
constexpr int kSkySppFactor = kEmissionSppFactor;
// A sky texel's batch, [spp, spp (1 + max(hard_spp_factor, kSkySppFactor))), ends before the deep
// texels' first sample, spp (1 + hard_spp_factor + kEmissionEdgeSppFactor), whatever the factor.
static_assert(kSkySppFactor <= kEmissionEdgeSppFactor, "the sky batch would overlap the deep batch");

// Balancing: a texel's share replaces its own directions where it is at least kBalanceGain x
// them, at most kMostBalanceSppFactor x spp, numbered after every other batch of the texel.
constexpr double kBalanceGain = 2.0;
constexpr int kMostBalanceSppFactor = 256;
constexpr int kBalanceFirstSppFactor = 1 << 16;

// Strata pairs for a texel's variance from their differences (hard batches), else its samples'
// spread, which counts an edge the strata resolve (docs/probes-estimator.md, "Sharing between neighbours").
constexpr int kMinStrataPairs = 8;

// The variance the cache's fill noise adds to the mean of `count` samples, from their
// (block, sigma): one error within a block of cells, independent errors across blocks
// (docs/probes.md, "Per-texel standard error").
float shared_cache_variance(std::vector<std::pair<uint64_t, float>>* errors, int count) {
  if (errors->empty() || count <= 0) return 0.0f;
  std::sort(errors->begin(), errors->end());
  double variance = 0.0, block_sum = 0.0;
  for (size_t k = 0; k < errors->size(); ++k) {
    block_sum += (*errors)[k].second;
    if (k + 1 == errors->size() || (*errors)[k + 1].first != (*errors)[k].first) {
      variance += block_sum * block_sum;
      block_sum = 0.0;
    }
  }
  return float(variance / (double(count) * double(count)));
}

}  // namespace

// A texel's first samples. finish_texel gives hard ones (glass, a glossy surface or a light met; a spread
// or a step from a neighbour over the threshold) fresh samples: no choice looks at those it keeps.
void ProbeView::first_look(TileProbe& probe, int t, int pass, Worker* w) {
  const int row = t / layout_.res_width, col = t % layout_.res_width;
  TexelState& s = probe.texels[size_t(t)];
  s = TexelState{Texel{&probe, t, row, col, ProbeTexel(row, col, layout_.res_height, layout_.res_width),
                       pass == 0 && correct_foot_ ? &probe.measured : nullptr, std::numeric_limits<float>::infinity()}};
  s.looked = true;
  if (probe.lit[size_t(t)] != 0) {
    s.part = Part::kRest;
    if (look_at_light(s, w)) return;  // a light's outline: supersampled from the start
  }
  s.first = estimate(s.x, 0, settings_.spp, s.part, &s.seen, &s.spread, w);
  s.x.samples = settings_.spp;
}

void ProbeView::measure_texel(TexelState& s) const {
  Texel& x = s.x;
  if (!x.measure) return;
  if (s.part == Part::kRest) {  // the texel's whole light: its rest and its emission
    x.cos_all += s.exact_cos;
    x.cos_emitted = s.exact_cos;
  }
  const float cosine = x.measure->cosine(x.cone.direction(glm::vec2(0.5f)));
  x.measure->add_texel(x.cos_all, x.cos_emitted, equirect_texel_solid_angle(x.row, layout_.res_width, layout_.res_height),
                       (x.variance + x.cache_variance) * cosine * cosine);
}

void ProbeView::finish_texel(TileProbe& probe, int t, Worker* w) {
  TexelState& s = probe.texels[size_t(t)];
  s.value = s.first;
  if (s.done) return;
  const int spp = settings_.spp;
  // Judged against the whole value: light known exactly makes the same spread matter less.
  const float limit = settings_.spread_threshold * (luminance(s.first) + luminance(s.exact) + transport_.dark_floor());
  const float step = s.part == Part::kAll ? neighbour_step(probe, t) : 0.0f;
  const bool own = (s.seen & TexelEstimator::kSeenHard) || (spp > 1 && s.spread > limit) || step > limit;
  if (own) note_choice(s.x, kHardTexel);
  // A later pass also supersamples what an earlier one found (docs/probes.md, "Accuracy as a target").
  const bool hard = own || earlier_choice(s.x) >= kHardTexel;
  if (!hard || !adaptive_) return;
  ++w->stats.supersampled_texels;
  s.value = hard_estimate(s, w);
}

glm::vec3 ProbeView::hard_estimate(TexelState& s, Worker* w) {
  const int spp = settings_.spp;
  const bool sky = s.seen & TexelEstimator::kSeenSky;
  const int hard_spp = spp * (sky ? std::max(settings_.hard_spp_factor, kSkySppFactor) : settings_.hard_spp_factor);
  uint8_t unused = 0;
  const bool deep_before = earlier_ && earlier_choice(s.x) >= kDeepTexel;
  if (!deep_before) {
    s.x.samples = hard_spp;
    float hard_spread = 0.0f;
    const glm::vec3 value = estimate(s.x, spp, hard_spp, s.part, &unused, &hard_spread, w);
    const bool own = hard_spread > kDeepSpreadRatio * (luminance(value) + luminance(s.exact) + transport_.dark_floor());
    if (own) note_choice(s.x, kDeepTexel);
    if (!own) return value;
  }
  // A rare bright part: more fresh samples, numbered after every other batch (emission's and
  // a sky texel's included).
  ++w->stats.deep_texels;
  s.x.samples = hard_spp * kDeepSppFactor;
  return estimate(s.x, spp * (1 + settings_.hard_spp_factor + kEmissionEdgeSppFactor), s.x.samples, s.part, &unused,
                  nullptr, w);
}

void ProbeView::balance(Worker* w) {
  if (!adaptive_ || !(settings_.balance > 0.0f)) return;
  // Neyman's allocation over the tile's probes: the extra directions in proportion to each
  // texel's noise per direction, in luminance, whichever probe it is in (the least summed variance).
  auto per_direction = [](const Texel& x) { return std::sqrt(std::max(x.variance, 0.0f) * float(x.samples)); };
  double noise = 0.0, spent = 0.0;
  for (const TileProbe& probe : w->tile)
    for (const TexelState& s : probe.texels)
      if (s.looked) noise += per_direction(s.x), spent += s.x.samples;
  if (!(noise > 0.0)) return;
  const double extra = double(settings_.balance) * spent;
  for (TileProbe& probe : w->tile)
    for (TexelState& s : probe.texels)  // the looked ones are this pass's
      if (s.looked) rebalance(s, extra * per_direction(s.x) / noise, w);
}

void ProbeView::rebalance(TexelState& s, double share, Worker* w) {
  // Fresh directions replace its own: these chose it, and kept they would bias its value.
  if (share < kBalanceGain * s.x.samples) return;
  s.x.samples = std::min(int(std::ceil(share)), settings_.spp * kMostBalanceSppFactor);
  // The photons' count as spp / its directions (balance heuristic, a photon a 16th of a direction).
  s.x.photon_scale = float(settings_.spp) / float(s.x.samples);
  uint8_t unused = 0;
  s.value = estimate(s.x, kBalanceFirstSppFactor * settings_.spp, s.x.samples, s.part, &unused, nullptr, w);
  ++w->stats.balanced_texels;
}

void ProbeView::note_choice(const Texel& x, TexelChoice choice) {
  if (out_.texel_choices.empty()) return;
  uint8_t& noted = out_.texel_choices[size_t(texel_id(x.probe->p, x.t))];
  noted = std::max(noted, uint8_t(choice));
}

TexelChoice ProbeView::earlier_choice(const Texel& x) const {
  return earlier_ ? TexelChoice((*earlier_)[size_t(texel_id(x.probe->p, x.t))]) : kPlainTexel;
}

float ProbeView::neighbour_step(const TileProbe& probe, int t) const {
  // The 8 neighbours (columns wrap) of the same pass whose first value is plain.
  const int row = t / layout_.res_width, col = t % layout_.res_width;
  const float own = luminance(probe.texels[size_t(t)].first);
  float step = 0.0f;
  for (int dr = -1; dr <= 1; ++dr) {
    const int r = row + dr;
    if (r < 0 || r >= layout_.res_height) continue;
    for (int dc = -1; dc <= 1; ++dc) {
      const int c = (col + dc + layout_.res_width) % layout_.res_width;
      const TexelState& n = probe.texels[size_t(r * layout_.res_width + c)];
      if (!n.looked || n.part != Part::kAll || (dr == 0 && dc == 0)) continue;
      step = std::max(step, std::abs(luminance(n.first) - own));
    }
  }
  return step;
}

// A texel a light may cover: its emission seen first estimated apart. Where a light's outline
// crosses it the rest is supersampled from the start (returns true); elsewhere judged as any texel.
bool ProbeView::look_at_light(TexelState& s, Worker* w) {
  const int spp = settings_.spp, hard_spp = spp * settings_.hard_spp_factor;
  Texel& x = s.x;
  TileProbe& probe = *x.probe;
  const bool edge = probe.lit[size_t(x.t)] == EmitterFootprints::kEdge;
  const uint64_t rays_before = w->stats.counters.rays;
  if (probe.analytic) {
    probe.lights.texel_pieces(x.row, x.col, layout_.res_height, layout_.res_width, &w->pieces);
    Rng rng = item_stream(probe_seed_, texel_id(probe.p, x.t), Purpose::kProbeLightPart);
    s.exact = visible_emission(probe.lights, w->pieces, scene_.accelerator(), out_.sites[size_t(probe.p)].origin,
                               spp * (edge ? kLightPartEdgeSppFactor : kLightPartSppFactor), rng, probe.measured,
                               &s.exact_cos, &w->strata, &w->stats.counters.rays);
  } else {
    uint8_t unused = 0;
    s.exact = estimate(x, spp + hard_spp, spp * (edge ? kEmissionEdgeSppFactor : kEmissionSppFactor), Part::kEmission,
                       &unused, nullptr, w);
    s.exact_cos = x.cos_emitted;
  }
  w->stats.emission_rays += w->stats.counters.rays - rays_before;
  w->stats.light_edge_texels += edge;
  ++w->stats.light_texels;
  if (!edge) return false;
  s.first = hard_estimate(s, w);
  s.done = true;
  ++w->stats.supersampled_texels;
  return true;
}

// `spread` (if given): the samples' luminance range. x.cos_all, x.cos_emitted: the mean radiance
// and its emitted part x the cosine to the probe's normal where the texel is measured, else 0.
glm::vec3 ProbeView::estimate(Texel& x, int first, int count, Part part, uint8_t* seen, float* spread, Worker* w) {
  TileProbe& probe = *x.probe;
  const uint64_t id = texel_id(probe.p, x.t);
  Rng permutation = item_stream(probe_seed_, id, Purpose::kProbeStrata, uint64_t(first));
  // The interleaving key is the same for every probe (texel and batch only).
  probe.interleave.key = item_stream_key(probe_seed_, uint64_t(x.t), Purpose::kProbeInterleave, uint64_t(first));
  stratified_square(count, permutation, &w->strata, probe.interleave);
  const glm::vec3 origin = out_.sites[size_t(probe.p)].origin;
  const float solid_angle = equirect_texel_solid_angle(x.row, layout_.res_width, layout_.res_height);
  glm::dvec3 sum(0.0), sum_cos(0.0), sum_emitted_cos(0.0);
  double sum_y = 0.0, sum_y2 = 0.0;
  w->luminances.clear();
  w->cache_errors.clear();
  float lo = std::numeric_limits<float>::infinity(), hi = 0.0f;
  for (int s = 0; s < count; ++s) {
    const uint64_t key = sample_key(probe_seed_, id, uint64_t(first + s));
    const Ray ray{origin, x.cone.direction(w->strata[size_t(s)])};
    TexelEstimator::SampleNotes notes;
    glm::vec3 L = transport_.estimator().sample(ray, key, part, probe.foot, solid_angle * x.photon_scale, &notes,
                                                &w->stats.counters);
    glm::vec3& emitted = notes.emitted;
    if (!is_finite(L) || !is_finite(emitted)) {
      ++w->stats.counters.nonfinite_samples;
      L = emitted = glm::vec3(0.0f);
    }
    *seen |= notes.seen;
    x.distance = std::min(x.distance, notes.distance);
    for (int r = 0; r < notes.cache_reads; ++r) w->cache_errors.push_back(notes.cache[size_t(r)]);
    sum += glm::dvec3(L);
    if (x.measure) {
      const double cosine = x.measure->cosine(ray.direction);
      sum_cos += glm::dvec3(L) * cosine;
      sum_emitted_cos += glm::dvec3(emitted) * cosine;
    }
    const float y = luminance(L);
    sum_y += y, sum_y2 += double(y) * y;
    w->luminances.push_back(y);
    lo = std::min(lo, y);
    hi = std::max(hi, y);
  }
  x.variance = float(stratified_mean_variance(w->strata, w->luminances, kMinStrataPairs));
  if (!(x.variance >= 0.0f))
    x.variance = count > 1 ? float(std::max(sum_y2 - sum_y * sum_y / count, 0.0) / (double(count) * (count - 1))) : 0.0f;
  x.cache_variance = shared_cache_variance(&w->cache_errors, count);
  if (spread) *spread = count > 0 ? hi - lo : 0.0f;
  x.cos_all = glm::vec3(sum_cos / double(count));
  x.cos_emitted = glm::vec3(sum_emitted_cos / double(count));
  return glm::vec3(sum / double(count));
}

void ProbeView::store_texel(const Texel& x, glm::vec3 value, const glm::vec3& seen_emission, Worker* w) {
  // The control variate can make a dark texel's mean negative: clamped to 0, and counted.
  if (glm::min(value.x, glm::min(value.y, value.z)) < 0.0f) {
    value = glm::max(value, glm::vec3(0.0f));
    ++w->stats.negative_texels;
  }
  const int p = x.probe->p;
  const uint64_t id = texel_id(p, x.t);
  if (!out_.texel_samples.empty()) out_.texel_samples[size_t(id)] = float(x.samples);
  if (share_) {
    records_.distance[size_t(id)] = x.distance;
    records_.samples[size_t(id)] = float(x.samples);
    records_.variance[size_t(id)] = x.variance;
    records_.cache_variance[size_t(id)] = x.cache_variance;
    // Emission seen directly is not shared: a light's edge moves with the slightest parallax.
    if (x.probe->lit[size_t(x.t)]) w->emission_seen.push_back({id, seen_emission});
  } else {
    value += seen_emission;
  }
  const glm::ivec2 at = layout_.mosaic_pixel(p, x.t);
  for (int ch = 0; ch < 3; ++ch) out_.mosaic.at(at.x, at.y, ch) = value[ch];
  out_.standard_error.at(at.x, at.y, 0) = std::sqrt(std::max(x.variance + x.cache_variance, 0.0f));
}

}  // namespace phyir::render
