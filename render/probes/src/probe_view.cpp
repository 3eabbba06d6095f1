#include "probe_view.h"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>

#include "phyir/core/error.h"
#include "phyir/core/progress.h"
#include "phyir/core/safe_math.h"
#include "phyir/render/equirect.h"
#include "phyir/render/streams.h"
#include "probe_standard_error.h"
#include "punctual_deposit.h"
#include "visible_emission.h"

namespace phyir::render {

namespace {

using Clock = std::chrono::steady_clock;

double seconds_since(Clock::time_point start) {
  return std::chrono::duration<double>(Clock::now() - start).count();
}

// Directions per texel for the emission seen in texels a light may cover, in units of spp.
// Where the lights' exact coverage is known (EmitterCoverage) they are drawn inside the
// covered parts and ask only whether an occluder hides the light (visible_emission): 4 x 4
// = 16 at the default spp, 64 x 4 = 256 where a light's outline crosses the texel
// (EmitterFootprints::kEdge), where an occluder's edge may too (a housing's rim in front of
// a panel). Measured on the bench (docs/probes.md): 2 and 32 x spp raise the error by 3%;
// 16 and 256 x spp over the whole texel change nothing. Otherwise (textured lights, an
// environment) they are spread over the texel, one ray each: 16 and 256 x spp.
// A hard texel whose hard samples spread over more than kDeepSpreadRatio x (their mean + the
// floor) holds a part far brighter than the rest that only some of them found (a lamp's halo
// on the ceiling, the sun in a polished surface): it is estimated once more from
// kDeepSppFactor x hard_spp fresh samples. Measured on the suite, 32x64 grid (docs/probes.md): the night
// apartment's error 0.55 -> 0.41-0.50 for 20% more CPU, the hard room's 7.5% -> 6.8%, the
// others within their seed-to-seed noise for 1-11% more CPU.
constexpr int kDeepSppFactor = 4;
constexpr float kDeepSpreadRatio = 4.0f;

constexpr int kLightPartSppFactor = 4;
constexpr int kLightPartEdgeSppFactor = 64;
constexpr int kEmissionSppFactor = 16;
constexpr int kEmissionEdgeSppFactor = 256;

// A texel's variance (what sharing tests its neighbours' values against) comes from its
// strata's differences where its samples make at least this many pairs of cells (the hard
// batches, spp x hard_spp_factor and more), else from their spread: at the window's edge
// seen from a sofa the spread counted the sill-to-sky step that stratification resolves,
// and let neighbours whose sill sits a fifth of a texel away average in.
constexpr int kMinStrataPairs = 8;

// The foot correction needs this many probes to tell the difference common to all of them
// (the last bounce) from each one's own (foot_correction.h).
constexpr size_t kMinFootCorrections = 64;

// A texel's spread is judged against its mean plus a floor, so that the noise of nearly
// black texels does not flag them: this fraction of the mean radiance a diffuse white
// surface would reflect under the cache's mean irradiance (a scale of the view's brightness
// that exists before any probe is shaded).
constexpr float kDarkFloorFraction = 0.1f;

// Probes are shaded in tiles of kTileRows x kTileCols neighbours on the grid, texel by texel
// across the tile: neighbouring probes see the same scene in the same direction from points
// a few centimetres apart, so one probe's texel finds the cache cells, BVH nodes and texture
// texels of the previous probe's still in the processor's caches (probe by probe, a probe's
// 512 texels cover the whole room first).
constexpr int kTileRows = 8;
constexpr int kTileCols = 8;

// The indices into `todo` of each tile's probes, tiles in grid order, each tile's probes in
// todo's order.
std::vector<std::vector<size_t>> probe_tiles(const std::vector<int>& todo, int grid_width) {
  const int tiles_across = (grid_width + kTileCols - 1) / kTileCols;
  auto tile_of = [&](int p) { return (p / grid_width / kTileRows) * tiles_across + (p % grid_width) / kTileCols; };
  std::vector<size_t> order(todo.size());
  for (size_t k = 0; k < order.size(); ++k) order[k] = k;
  std::stable_sort(order.begin(), order.end(), [&](size_t a, size_t b) { return tile_of(todo[a]) < tile_of(todo[b]); });
  std::vector<std::vector<size_t>> tiles;
  for (size_t n = 0; n < order.size(); ++n) {
    if (n == 0 || tile_of(todo[order[n]]) != tile_of(todo[order[n - 1]])) tiles.emplace_back();
    tiles.back().push_back(order[n]);
  }
  return tiles;
}

}  // namespace

ProbeView::ProbeView(const RenderScene& scene, const Effects& effects, const ProbeSettings& settings,
                     std::vector<ProbeSite> sites, const std::vector<int>& subset)
    : scene_(scene),
      effects_(effects),
      settings_(settings),
      layout_(settings.layout),
      texels_(settings.layout.texels_per_probe()),
      probe_seed_(stream_key(settings.seed, Purpose::kProbeSeed)),  // apart from color.exr's streams
      adaptive_(settings.mode == ProbeMode::kCache && settings.hard_spp_factor > 1),
      share_(settings.mode == ProbeMode::kCache && settings.sharing.radius > 0),
      correct_foot_(settings.mode == ProbeMode::kCache && settings.correct_foot),
      footprints_(scene.scene()),
      coverage_(scene.scene()),
      cones_(settings.layout.res_height, settings.layout.res_width) {
  if (sites.size() != size_t(layout_.probe_count()))
    fail("{} probe sites given for a {}x{} grid", sites.size(), layout_.grid_height, layout_.grid_width);
  out_.layout = layout_;
  out_.sites = std::move(sites);
  out_.mosaic = Image(layout_.mosaic_width(), layout_.mosaic_height(), 3);
  out_.standard_error = Image(layout_.mosaic_width(), layout_.mosaic_height(), 1);
  out_.position = Image(layout_.grid_width, layout_.grid_height, 3);
  out_.normal = Image(layout_.grid_width, layout_.grid_height, 3);
  out_.mask = Image(layout_.grid_width, layout_.grid_height, 1);
  for (int p : subset)
    if (p < 0 || p >= layout_.probe_count())
      fail("probe index {} outside the {}x{} grid", p, layout_.grid_height, layout_.grid_width);
  select_probes();
  if (subset.empty()) return;
  todo_.clear();
  for (int p : subset)
    if (out_.sites[size_t(p)].computed()) todo_.push_back(p);
  out_.stats.computed_probes = todo_.size();
}

ProbeOutput ProbeView::run() {
  const auto start = Clock::now();
  tiles_ = probe_tiles(todo_, layout_.grid_width);
  if (settings_.mode == ProbeMode::kCache) build_cache();
  const auto shade_start = Clock::now();
  if (settings_.mode == ProbeMode::kCache && effects_.punctual_lights && settings_.path.max_bounces >= 1) {
    uint64_t rays = 0;
    scenes::Bounds surroundings;  // where the sun's photons matter: round the view's probes
    for (const ProbeSite& site : out_.sites) {
      if (!site.computed()) continue;
      surroundings.extend(site.surface);
      surroundings.extend(site.origin);
    }
    photons_ = PunctualPhotons(scene_, settings_.photons_per_light, settings_.spp, surroundings,
                               stream_key(settings_.seed, Purpose::kProbePhoton), &rays);
    out_.stats.photons = photons_.size();
    out_.stats.photon_rays += rays;
    out_.stats.counters.rays += rays;
  }
  estimator_ = std::make_unique<TexelEstimator>(scene_, effects_, settings_, cache_.get(), &photons_);
  if (share_) {
    records_.distance.assign(size_t(layout_.probe_count()) * size_t(texels_), std::numeric_limits<float>::infinity());
    records_.samples.assign(size_t(layout_.probe_count()) * size_t(texels_), 0.0f);
    records_.variance.assign(size_t(layout_.probe_count()) * size_t(texels_), 0.0f);
  }
  feet_.assign(correct_foot_ ? todo_.size() : 0, FootCorrection());
  Progress progress("probes", todo_.size() * (correct_foot_ ? 2 : 1), correct_foot_ ? "probe halves" : "probes",
                    settings_.progress);
  progress_ = &progress;
  shade_pass(0);
  if (correct_foot_) {
    correct_feet();
    shade_pass(1);
  }
  progress.finish();
  ProbeStats& stats = out_.stats;
  for (const Worker& w : workers_) stats += w.stats;
  if (cache_) stats.cache_fallbacks = cache_->fallbacks();
  stats.shade_seconds = seconds_since(shade_start);
  if (share_) share_between_neighbours();
  add_after_sharing(&Worker::photon_light);
  if (effects_.punctual_lights && settings_.punctual_lights)
    stats.counters.rays += deposit_punctual_lights(scene_, layout_, out_.sites, todo_, &out_.mosaic);
  out_.standard_error = pooled_standard_error(out_.standard_error, layout_);
  stats.total_seconds = seconds_since(start);
  return std::move(out_);
}

void ProbeView::select_probes() {
  ProbeStats& stats = out_.stats;
  for (int p = 0; p < layout_.probe_count(); ++p) {
    const ProbeSite& s = out_.sites[size_t(p)];
    const int i = p / layout_.grid_width, j = p % layout_.grid_width;
    ++stats.probes;
    switch (s.status) {
      case ProbeStatus::kValid: ++stats.valid; break;
      case ProbeStatus::kNothing: ++stats.nothing; break;
      case ProbeStatus::kEmitter: ++stats.emitter; break;
      case ProbeStatus::kTransparent: ++stats.transparent; break;
    }
    if (!s.computed()) continue;
    for (int c = 0; c < 3; ++c) {
      out_.position.at(j, i, c) = s.origin[c];
      out_.normal.at(j, i, c) = s.normal[c];
    }
    out_.mask.at(j, i) = s.valid() ? 1.0f : 0.0f;
    todo_.push_back(p);
  }
  stats.computed_probes = todo_.size();
}

void ProbeView::build_cache() {
  const auto start = Clock::now();
  RadianceCacheSettings cs = settings_.cache;
  cs.seed = stream_key(settings_.seed, Purpose::kCacheSeed);
  cs.progress = settings_.progress;
  cache_ = std::make_unique<RadianceCache>(scene_, effects_, settings_.path, cs);
  // Discovery: one direction per texel, tile by tile, texel by texel across a tile (as the
  // shading): neighbouring probes' rays offer points to the same cells one after the other.
  tbb::enumerable_thread_specific<RadianceCache::Collector> collectors;
  tbb::parallel_for(tbb::blocked_range<size_t>(0, tiles_.size(), 1), [&](const tbb::blocked_range<size_t>& r) {
    RadianceCache::Collector& collector = collectors.local();
    PathCounters& c = workers_.local().stats.counters;
    for (size_t n = r.begin(); n < r.end(); ++n) {
      for (int t = 0; t < texels_; ++t) {
        for (size_t k : tiles_[n]) {
          const int p = todo_[k];
          const uint64_t key = item_stream_key(probe_seed_, texel_id(p, t), Purpose::kProbeDiscovery);
          Rng rng = generator(key, Purpose::kProbeDiscovery);
          const Ray ray{out_.sites[size_t(p)].origin,
                        probe_texel_direction(t / layout_.res_width, t % layout_.res_width, layout_.res_height,
                                              layout_.res_width, rng.next_2d())};
          SurfaceInteraction si;
          ++c.rays;
          if (scene_.trace(ray, &si) && !(si.transmission > 0.0f))
            collector.offer(*cache_, cache_point(si, si.shading_normal), stream_key(key, Purpose::kProbeCacheTieBreak));
        }
      }
    }
  });
  std::vector<const RadianceCache::Collector*> list;
  for (const auto& collector : collectors) list.push_back(&collector);
  ProbeStats& stats = out_.stats;
  cache_->build(list, &stats.counters);
  stats.cache_rays = stats.counters.rays;  // the fill's; the discovery's are the workers' so far
  for (const Worker& w : workers_) stats.cache_rays += w.stats.counters.rays;
  stats.cache_cells = cache_->cell_count();
  stats.cache_direct_cells = cache_->direct_cell_count();
  stats.cache_edge_cells = cache_->edge_cell_count();
  stats.cache_edge_profiles = cache_->edge_profile_count();
  stats.cache_fill_samples = cache_->fill_samples();
  stats.cache_seconds = seconds_since(start);
  dark_floor_ = kDarkFloorFraction * cache_->mean_irradiance_luminance() * kInvPi;
}

void ProbeView::shade_pass(int pass) {
  tbb::parallel_for(
      tbb::blocked_range<size_t>(0, tiles_.size(), 1),
      [&](const tbb::blocked_range<size_t>& r) {
        Worker& w = workers_.local();
        for (size_t n = r.begin(); n < r.end(); ++n) shade_tile(tiles_[n], pass, &w);
      },
      tbb::simple_partitioner());
}

void ProbeView::shade_tile(const std::vector<size_t>& tile, int pass, Worker* w) {
  w->tile.resize(tile.size());
  for (size_t m = 0; m < tile.size(); ++m) {
    w->tile[m].k = tile[m];
    w->tile[m].p = todo_[tile[m]];
    prepare_probe(&w->tile[m], pass);
    if (pass == 0 && !photons_.empty()) gather_photons(w->tile[m], w);
  }
  for (TileProbe& probe : w->tile) probe.texels.assign(size_t(texels_), TexelState());
  for (int t = 0; t < texels_; ++t)
    for (TileProbe& probe : w->tile)
      if (in_pass(probe, t, pass)) first_look(probe, t, pass, w);
  for (int t = 0; t < texels_; ++t)
    for (TileProbe& probe : w->tile)
      if (in_pass(probe, t, pass)) finish_texel(probe, t, w);
  if (pass == 0 && correct_foot_)
    for (const TileProbe& probe : w->tile)
      feet_[probe.k] = FootCorrection::measure(*cache_, out_.sites[size_t(probe.p)], probe.measured);
  progress_->advance(tile.size());
}

// The texels a pass shades: all of them, or with the foot correction those that may look to
// the front (pass 0) and those facing the probe's own surface (pass 1).
bool ProbeView::in_pass(const TileProbe& probe, int t, int pass) const {
  return !correct_foot_ || (pass == 1) == cones_.faces_away(t, out_.sites[size_t(probe.p)].normal);
}

void ProbeView::prepare_probe(TileProbe* probe, int pass) const {
  const int p = probe->p;
  const ProbeSite& site = out_.sites[size_t(p)];
  probe->interleave = Interleave();
  if (share_) {
    probe->interleave.sub = sub_stratum(p / layout_.grid_width, p % layout_.grid_width, settings_.sharing);
    probe->interleave.count = settings_.sharing.window();
  }
  probe->lit.assign(size_t(texels_), uint8_t(0));
  if (adaptive_) footprints_.mark(site.origin, layout_.res_height, layout_.res_width, &probe->lit);
  // The lights' exact coverage of each texel, where the emission a texel sees is the
  // lights' alone (no environment).
  probe->lights = EmitterCoverage::View();
  probe->analytic = false;
  bool any_lit = false;
  for (int t = 0; t < texels_ && !any_lit; ++t) any_lit = probe->lit[size_t(t)] != 0 && in_pass(*probe, t, pass);
  if (adaptive_ && coverage_.usable() && !effects_.environment && any_lit) {
    probe->lights = coverage_.view(site.origin);
    probe->analytic = probe->lights.valid();
  }
  probe->measured = FootIrradiance(site.normal);
  probe->foot = pass == 1 ? feet_[probe->k].less(common_difference_) : FootCorrection();
}

// A texel's first samples, then its final value: hard texels (the first samples met glass,
// a glossy surface or a light whose emission is not estimated apart; or they spread over
// more than spread_threshold x (their mean + a floor); or the texel's first value steps by
// as much from a neighbour's: an edge, a highlight, a shadow boundary or a sun patch runs
// through it) are estimated again from hard_spp_factor x spp fresh samples. The neighbours'
// test finds the texels whose few first samples all fell on one side of an edge: a sun
// patch's rim seen from a ceiling probe, a lamp shade lit from inside seen from the floor.
// No decision looks at the samples it selects, so none biases the value.
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
  s.first = estimate(s.x, 0, settings_.spp, s.part, &s.hard, &s.spread, w);
  s.x.samples = settings_.spp;
}

void ProbeView::finish_texel(TileProbe& probe, int t, Worker* w) {
  TexelState& s = probe.texels[size_t(t)];
  glm::vec3 value = s.done ? s.first : settle(probe, t, w);
  Texel& x = s.x;
  if (s.part == Part::kRest) {  // the texel's whole light: its rest and its emission
    x.cos_all += s.exact_cos;
    x.cos_emitted = s.exact_cos;
  }
  if (x.measure)
    x.measure->add_texel(x.cos_all, x.cos_emitted, equirect_texel_solid_angle(x.row, layout_.res_width, layout_.res_height));
  store_texel(x, value, s.exact, w);
}

glm::vec3 ProbeView::settle(TileProbe& probe, int t, Worker* w) {
  TexelState& s = probe.texels[size_t(t)];
  const int spp = settings_.spp;
  // The spread is judged against the texel's whole value: light it has exactly (the
  // emission seen directly, estimated apart) makes the same spread matter less.
  const float limit = settings_.spread_threshold * (luminance(s.first) + luminance(s.exact) + dark_floor_);
  const float step = s.part == Part::kAll ? neighbour_step(probe, t) : 0.0f;
  const bool hard = s.hard || (spp > 1 && s.spread > limit) || step > limit;
  if (!hard || !adaptive_) return s.first;
  ++w->stats.supersampled_texels;
  return hard_estimate(s, w);
}

glm::vec3 ProbeView::hard_estimate(TexelState& s, Worker* w) {
  const int spp = settings_.spp, hard_spp = spp * settings_.hard_spp_factor;
  bool unused = false;
  s.x.samples = hard_spp;
  float hard_spread = 0.0f;
  const glm::vec3 value = estimate(s.x, spp, hard_spp, s.part, &unused, &hard_spread, w);
  if (!(hard_spread > kDeepSpreadRatio * (luminance(value) + luminance(s.exact) + dark_floor_)))
    return value;
  // A rare bright part (a sun patch's rim, a lamp's halo on the ceiling) that few of the
  // hard samples found: its share of the texel is still a guess. Fresh samples again, more,
  // numbered after every other batch of the texel (its light's emission included).
  ++w->stats.deep_texels;
  s.x.samples = hard_spp * kDeepSppFactor;
  return estimate(s.x, spp * (1 + settings_.hard_spp_factor + kEmissionEdgeSppFactor), s.x.samples, s.part, &unused,
                  nullptr, w);
}

float ProbeView::neighbour_step(const TileProbe& probe, int t) const {
  // The 8 neighbours in the probe's image (columns wrap round), those of the same pass whose
  // first value is plain (no light estimated apart).
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

// A texel a light may cover (EmitterFootprints): the emission seen first is estimated apart
// (partial coverage of a light is the largest error otherwise), the rest from its own
// samples. Where a light's outline crosses the texel the rest straddles it (the light's
// reflection on one side, what lies beyond on the other) and is supersampled from the
// start (returns true); elsewhere the light covers the texel wholly or not at all, and the
// rest is hard only by its own first samples, as in any texel.
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
    bool unused = false;
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

// `spread` (if given) receives the range of the samples' luminances; x.cos_all and
// x.cos_emitted the sample means of the radiance and its emitted part times the cosine to
// the probe's normal when the texel is measured (FootIrradiance), else 0.
glm::vec3 ProbeView::estimate(Texel& x, int first, int count, Part part, bool* saw_hard, float* spread, Worker* w) {
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
  float lo = std::numeric_limits<float>::infinity(), hi = 0.0f;
  for (int s = 0; s < count; ++s) {
    const uint64_t key = sample_key(probe_seed_, id, uint64_t(first + s));
    const Ray ray{origin, x.cone.direction(w->strata[size_t(s)])};
    glm::vec3 emitted;
    glm::vec3 L = estimator_->sample(ray, key, part, probe.foot, solid_angle, saw_hard, &x.distance, &emitted,
                                     &w->stats.counters);
    if (!is_finite(L) || !is_finite(emitted)) {
      ++w->stats.counters.nonfinite_samples;
      L = emitted = glm::vec3(0.0f);
    }
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
  if (spread) *spread = count > 0 ? hi - lo : 0.0f;
  x.cos_all = glm::vec3(sum_cos / double(count));
  x.cos_emitted = glm::vec3(sum_emitted_cos / double(count));
  return glm::vec3(sum / double(count));
}

void ProbeView::store_texel(const Texel& x, glm::vec3 value, const glm::vec3& seen_emission, Worker* w) {
  // The specular control variate's corrections can be negative on their own; a texel whose
  // mean still is (dark, grazing, few directions) is clamped to 0, and counted.
  if (glm::min(value.x, glm::min(value.y, value.z)) < 0.0f) {
    value = glm::max(value, glm::vec3(0.0f));
    ++w->stats.negative_texels;
  }
  const int p = x.probe->p;
  const uint64_t id = texel_id(p, x.t);
  if (share_) {
    records_.distance[size_t(id)] = x.distance;
    records_.samples[size_t(id)] = float(x.samples);
    records_.variance[size_t(id)] = x.variance;
    // Emission seen directly is not shared: a light's edge moves across a texel with the
    // slightest parallax, and its own directions already resolve it.
    if (x.probe->lit[size_t(x.t)]) w->emission_seen.push_back({id, seen_emission});
  } else {
    value += seen_emission;
  }
  const glm::ivec2 at = layout_.mosaic_pixel(p, x.t);
  for (int ch = 0; ch < 3; ++ch) out_.mosaic.at(at.x, at.y, ch) = value[ch];
  out_.standard_error.at(at.x, at.y, 0) = std::sqrt(std::max(x.variance, 0.0f));
}

void ProbeView::gather_photons(TileProbe& probe, Worker* w) {
  const ProbeSite& site = out_.sites[size_t(probe.p)];
  uint64_t rays = 0;
  photons_.gather(site.origin, site.normal, layout_.res_height, layout_.res_width,
                  item_stream_key(probe_seed_, uint64_t(probe.p), Purpose::kProbePhotonRoulette), &w->photon_radiance,
                  &w->photon_radiance_cos, &rays);
  w->stats.counters.rays += rays;
  w->stats.photon_rays += rays;
  for (int t = 0; t < texels_; ++t) {
    const glm::vec3& value = w->photon_radiance[size_t(t)];
    if (!(max_component(value) > 0.0f)) continue;
    w->photon_light.push_back({texel_id(probe.p, t), value});
    ++w->stats.photon_texels;
    if (correct_foot_ && in_pass(probe, t, 0))
      probe.measured.add_texel(w->photon_radiance_cos[size_t(t)], glm::vec3(0.0f),
                               equirect_texel_solid_angle(t / layout_.res_width, layout_.res_width, layout_.res_height));
  }
}

void ProbeView::add_after_sharing(const std::vector<std::pair<uint64_t, glm::vec3>> Worker::*list) {
  for (const Worker& w : workers_) {
    for (const auto& [id, value] : w.*list) {
      const glm::ivec2 at = layout_.mosaic_pixel(int(id / uint64_t(texels_)), int(id % uint64_t(texels_)));
      for (int ch = 0; ch < 3; ++ch) out_.mosaic.at(at.x, at.y, ch) += value[ch];
    }
  }
}

void ProbeView::correct_feet() {
  // The common difference is a mean over the probes: with few of them it would take most of
  // each probe's own difference with it, so then none is corrected.
  const size_t active =
      size_t(std::count_if(feet_.begin(), feet_.end(), [](const FootCorrection& f) { return f.active(); }));
  if (active < kMinFootCorrections) std::fill(feet_.begin(), feet_.end(), FootCorrection());
  common_difference_ = FootCorrection::common_difference(feet_);
  out_.stats.foot_corrections = active < kMinFootCorrections ? 0 : active;
  out_.stats.foot_common_difference = common_difference_;
}

void ProbeView::share_between_neighbours() {
  const auto start = Clock::now();
  std::vector<uint8_t> computed(size_t(layout_.probe_count()), 0);
  for (int p : todo_) computed[size_t(p)] = 1;
  out_.mosaic = render::share_between_neighbours(out_.mosaic, layout_, out_.sites, computed, records_,
                                                 settings_.sharing, &out_.stats.shared_texels);
  add_after_sharing(&Worker::emission_seen);
  out_.stats.share_seconds = seconds_since(start);
}

}  // namespace phyir::render
