#include "probe_view.h"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <limits>

#include "phyir/core/error.h"
#include "phyir/core/safe_math.h"
#include "phyir/core/stopwatch.h"
#include "phyir/render/equirect.h"
#include "phyir/render/streams.h"
#include "probe_standard_error.h"
#include "punctual_deposit.h"

namespace phyir::render {

namespace {

// Fewer probes cannot tell the difference common to all (the last bounce) from each one's
// own (foot_correction.h).
constexpr size_t kMinFootCorrections = 64;

// Tiles of neighbours, shaded texel by texel across the tile: the next probe's texel finds the
// same cells, BVH nodes and textures still in the processor's caches (docs/probes-estimator.md, "Tiles").
constexpr int kTileRows = 8;
constexpr int kTileCols = 8;

// The indices into `todo` of each tile's probes; tiles in grid order, probes in todo's order.
ProbeTiles probe_tiles(const std::vector<int>& todo, int grid_width) {
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
                     std::vector<ProbeSite> sites, const std::vector<int>& subset,
                     const std::vector<uint8_t>* earlier_choices)
    : scene_(scene),
      effects_(effects),
      settings_(settings),
      layout_(settings.layout),
      texels_(settings.layout.texels_per_probe()),
      probe_seed_(stream_key(settings.seed, Purpose::kProbeSeed)),  // apart from color.exr's streams
      adaptive_(settings.mode == ProbeMode::kCache && settings.hard_spp_factor > 1),
      share_(settings.mode == ProbeMode::kCache && settings.sharing.radius > 0),
      correct_foot_(settings.mode == ProbeMode::kCache && settings.correct_foot),
      transport_(scene, effects, settings),
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
  if (settings.target_error > 0.0f) {
    out_.texel_choices.assign(size_t(layout_.probe_count()) * size_t(texels_), kPlainTexel);
    out_.texel_samples.assign(size_t(layout_.probe_count()) * size_t(texels_), 0.0f);
  }
  if (earlier_choices && earlier_choices->size() == size_t(layout_.probe_count()) * size_t(texels_))
    earlier_ = earlier_choices;
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
  const Stopwatch total_watch;
  tiles_ = probe_tiles(todo_, layout_.grid_width);
  if (settings_.mode == ProbeMode::kCache) transport_.build_cache(out_.sites, todo_, tiles_, &out_.stats);
  const Stopwatch shade_watch;
  transport_.build_estimator(out_.sites, &out_.stats);
  if (share_) {
    records_.distance.assign(size_t(layout_.probe_count()) * size_t(texels_), std::numeric_limits<float>::infinity());
    records_.samples.assign(size_t(layout_.probe_count()) * size_t(texels_), 0.0f);
    records_.variance.assign(size_t(layout_.probe_count()) * size_t(texels_), 0.0f);
    records_.cache_variance.assign(size_t(layout_.probe_count()) * size_t(texels_), 0.0f);
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
  if (transport_.cache()) stats.cache_fallbacks = transport_.cache()->fallbacks();
  stats.shade_seconds = shade_watch.seconds();
  if (share_) share_between_neighbours();
  add_after_sharing(&Worker::photon_light);
  if (effects_.punctual_lights && settings_.punctual_lights)
    stats.counters.rays += deposit_punctual_lights(scene_, layout_, out_.sites, todo_, &out_.mosaic);
  out_.standard_error = pooled_standard_error(out_.standard_error, layout_);
  stats.total_seconds = total_watch.seconds();
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
  }
  for (TileProbe& probe : w->tile) probe.texels.assign(size_t(texels_), TexelState());
  for (int t = 0; t < texels_; ++t)
    for (TileProbe& probe : w->tile)
      if (in_pass(probe, t, pass)) first_look(probe, t, pass, w);
  for (int t = 0; t < texels_; ++t)
    for (TileProbe& probe : w->tile)
      if (in_pass(probe, t, pass)) finish_texel(probe, t, w);
  balance(w);
  for (TileProbe& probe : w->tile) {
    if (!transport_.photons().empty()) gather_photons(probe, pass, w);
    for (TexelState& s : probe.texels) {
      if (!s.looked) continue;
      measure_texel(s);
      store_texel(s.x, s.value, s.exact, w);
    }
  }
  if (pass == 0 && correct_foot_)
    for (const TileProbe& probe : w->tile)
      feet_[probe.k] = FootCorrection::measure(*transport_.cache(), out_.sites[size_t(probe.p)], probe.measured);
  progress_->advance(tile.size());
}

// All texels, or with the foot correction those that may look to the front (pass 0), then the rest.
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
  if (adaptive_) transport_.footprints().mark(site.origin, layout_.res_height, layout_.res_width, &probe->lit);
  // The lights' exact coverage, where the emission a texel sees is theirs alone (no environment).
  probe->lights = EmitterCoverage::View();
  probe->analytic = false;
  bool any_lit = false;
  for (int t = 0; t < texels_ && !any_lit; ++t) any_lit = probe->lit[size_t(t)] != 0 && in_pass(*probe, t, pass);
  if (adaptive_ && transport_.coverage().usable() && !effects_.environment && any_lit) {
    probe->lights = transport_.coverage().view(site.origin);
    probe->analytic = probe->lights.valid();
  }
  probe->measured = FootIrradiance(site.normal);
  probe->foot = pass == 1 ? feet_[probe->k].less(common_difference_) : FootCorrection();
}

void ProbeView::gather_photons(TileProbe& probe, int pass, Worker* w) {
  const ProbeSite& site = out_.sites[size_t(probe.p)];
  w->photon_scale.assign(size_t(texels_), 0.0f);
  for (int t = 0; t < texels_; ++t)
    if (probe.texels[size_t(t)].looked) w->photon_scale[size_t(t)] = probe.texels[size_t(t)].x.photon_scale;
  uint64_t rays = 0;
  const uint64_t key = item_stream_key(probe_seed_, uint64_t(probe.p), Purpose::kProbePhotonRoulette, uint64_t(pass));
  transport_.photons().gather(site.origin, site.normal, layout_.res_height, layout_.res_width, key, &w->photon_radiance,
                              &w->photon_radiance_cos, &rays, &w->photon_scale);
  w->stats.counters.rays += rays;
  w->stats.photon_rays += rays;
  for (int t = 0; t < texels_; ++t) {
    const glm::vec3& value = w->photon_radiance[size_t(t)];
    if (!(max_component(value) > 0.0f)) continue;
    w->photon_light.push_back({texel_id(probe.p, t), value});
    ++w->stats.photon_texels;
    if (probe.texels[size_t(t)].x.measure)
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
  // The common difference is a mean over the probes: with few, it takes each one's own with it.
  const size_t active =
      size_t(std::count_if(feet_.begin(), feet_.end(), [](const FootCorrection& f) { return f.active(); }));
  if (active < kMinFootCorrections) std::fill(feet_.begin(), feet_.end(), FootCorrection());
  common_difference_ = FootCorrection::common_difference(feet_);
  out_.stats.foot_corrections = active < kMinFootCorrections ? 0 : active;
  out_.stats.foot_common_difference = common_difference_;
}

void ProbeView::share_between_neighbours() {
  const Stopwatch watch;
  std::vector<uint8_t> computed(size_t(layout_.probe_count()), 0);
  for (int p : todo_) computed[size_t(p)] = 1;
  out_.mosaic = render::share_between_neighbours(out_.mosaic, layout_, out_.sites, computed, records_,
                                                 settings_.sharing, &out_.stats.shared_texels, &out_.standard_error);
  add_after_sharing(&Worker::emission_seen);
  out_.stats.share_seconds = watch.seconds();
}

}  // namespace phyir::render
