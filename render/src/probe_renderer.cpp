#include "phyir/render/probe_renderer.h"

#include <tbb/enumerable_thread_specific.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <chrono>
#include <limits>
#include <memory>

#include "phyir/core/error.h"
#include "phyir/core/progress.h"
#include "phyir/core/safe_math.h"
#include "phyir/render/emitter_coverage.h"
#include "phyir/render/emitter_footprints.h"
#include "phyir/render/equirect.h"
#include "phyir/render/foot_correction.h"
#include "phyir/render/probe_sharing.h"
#include "phyir/render/radiance_cache.h"
#include "phyir/render/streams.h"
#include "phyir/render/sampling.h"
#include "probe_texel_estimator.h"

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
// 16 and 256 x spp, which session 5 spent over the whole texel, change nothing. Otherwise
// (textured lights, an environment) they are spread over the texel, one ray each: 16 and
// 256 x spp.
constexpr int kLightPartSppFactor = 4;
constexpr int kLightPartEdgeSppFactor = 64;
constexpr int kEmissionSppFactor = 16;
constexpr int kEmissionEdgeSppFactor = 256;

// The foot correction needs this many probes to tell the difference common to all of them
// (the last bounce) from each one's own (foot_correction.h).
constexpr size_t kMinFootCorrections = 64;

// See dark_floor in render_probes_at.
constexpr float kDarkFloorFraction = 0.1f;

// Probes are shaded in tiles of kTileRows x kTileCols neighbours on the grid, texel by
// texel across the tile (see shade_pass).
constexpr int kTileRows = 8;
constexpr int kTileCols = 8;

// The indices into `todo` of each tile's probes, tiles in grid order, each tile's probes
// in todo's order.
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

// The emission a light texel sees, sampled only where the lights cover it. Each light
// triangle's part of the texel is known exactly (EmitterCoverage); `count` directions, split
// between the parts by their size, are drawn uniformly in solid angle inside them (stratified
// points of a part's bounding box in the equal-area (phi, cos theta) map, kept where they fall
// inside the triangle: the others cost no ray), and each asks only whether something hides
// the light. Where a light is in full view the estimate is exact; elsewhere every direction
// lands on the light, where an occluder's edge cuts it, none on the rest of the texel.
// *emission_cos receives the same times the cosine to the probe's normal (FootIrradiance).
glm::vec3 visible_emission(const EmitterCoverage::View& lights, const std::vector<EmitterCoverage::View::Piece>& pieces,
                           const Accelerator& accelerator, const glm::vec3& origin, int count, Rng& rng,
                           const FootIrradiance& foot, glm::vec3* emission_cos, std::vector<glm::vec2>* strata,
                           uint64_t* rays) {
  // A part's box is tight, so most points fall inside; a sliver may need a few rounds.
  constexpr int kMaxRounds = 4;
  // The occlusion test stops this fraction of the way short of the light's plane.
  constexpr float kShortOfTheLight = 1e-4f;
  double covered = 0.0;
  for (const auto& piece : pieces) covered += piece.fraction;
  glm::dvec3 sum(0.0), sum_cos(0.0);
  for (const auto& piece : pieces) {
    const int wanted = std::max(1, int(std::lround(count * piece.fraction / covered)));
    int inside = 0, visible = 0;
    double visible_cos = 0.0;
    glm::vec3 last(0.0f);
    for (int round = 0; round < kMaxRounds && 2 * inside < wanted; ++round) {
      stratified_square(wanted, rng, strata);
      for (const glm::vec2& a : *strata) {
        const double phi = piece.lo.x + double(a.x) * (piece.hi.x - piece.lo.x);
        const double z = std::clamp(piece.lo.y + double(a.y) * (piece.hi.y - piece.lo.y), -1.0, 1.0);
        const glm::vec3 d = equirect_direction(float(phi / kTwoPi + 0.5), float(z), float(std::sqrt(1.0 - z * z)));
        float distance = 0.0f;
        if (!lights.hits(piece.light, d, &distance)) continue;
        ++inside;
        ++*rays;
        last = d;
        if (accelerator.occluded(Ray{origin, d, 0.0f, distance * (1.0f - kShortOfTheLight)})) continue;
        ++visible;
        visible_cos += foot.cosine(d);
      }
    }
    // A sliver no point found is taken as in view (its share of the texel is negligible).
    const double seen = inside > 0 ? double(visible) / inside : 1.0;
    const double seen_cos = inside > 0 ? visible_cos / inside : foot.cosine(last);
    sum += glm::dvec3(piece.emission) * (piece.fraction * seen);
    sum_cos += glm::dvec3(piece.emission) * (piece.fraction * seen_cos);
  }
  *emission_cos = glm::vec3(sum_cos);
  return glm::vec3(sum);
}

}  // namespace

ProbeMode parse_probe_mode(const std::string& name) {
  if (name == "path") return ProbeMode::kPath;
  if (name == "cache") return ProbeMode::kCache;
  fail("--probe-mode '{}' is not one of: cache (the default, shared irradiance cache), path (unbiased reference)", name);
}

std::string probe_mode_name(ProbeMode mode) { return mode == ProbeMode::kPath ? "path" : "cache"; }

void ProbeSettings::validate() const {
  layout.validate();
  if (spp <= 0 || spp > 1 << 20) fail("--probe-spp {} must be between 1 and 2^20", spp);
  // Below 0.1 mm the origin is within a few float ulps (and ray offsets) of room-scale
  // geometry; above 1 m it is no longer "at" the surface.
  if (!(offset >= 1e-4f && offset <= 1.0f)) fail("--probe-offset {} must be between 1e-4 and 1 metre", offset);
  if (!(cache_cell >= 1e-3f && cache_cell <= 10.0f)) fail("--probe-cache-cell {} must be between 1e-3 and 10 metres", cache_cell);
  if (cache_spp <= 0 || cache_spp > 1 << 20) fail("--probe-cache-spp {} must be between 1 and 2^20", cache_spp);
  if (!(cache_direct_cells >= 0.0f && cache_direct_cells <= 1e6f))
    fail("--probe-cache-direct-cells {} must be between 0 (never) and 1e6 cells", cache_direct_cells);
  if (hard_spp_factor < 1 || hard_spp_factor > 1024) fail("hard-texel spp factor {} must be between 1 and 1024", hard_spp_factor);
  if (!(spread_threshold > 0.0f && spread_threshold <= 1e6f))
    fail("--probe-spread-threshold {} must be above 0 (and at most 1e6, i.e. never)", spread_threshold);
  // A 9x9 window is already ~20 cm across at the paper's grid: beyond it parallax rejects most texels.
  if (sharing.radius < 0 || sharing.radius > 4) fail("--probe-share-radius {} must be between 0 (off) and 4", sharing.radius);
  if (!(sharing.parallax_texels > 0.0f && sharing.parallax_texels <= 100.0f))
    fail("--probe-share-parallax {} must be above 0 and at most 100 texels", sharing.parallax_texels);
}

nlohmann::json ProbeSettings::to_json() const {
  nlohmann::json j = {{"grid", {layout.grid_height, layout.grid_width}},
                      {"resolution", {layout.res_height, layout.res_width}},
                      {"mosaic", {layout.mosaic_height(), layout.mosaic_width()}},
                      {"spp", spp},
                      {"mode", probe_mode_name(mode)},
                      {"origin_offset_m", offset},
                      {"seed", seed},
                      {"max_bounces", path.max_bounces}};
  if (mode == ProbeMode::kCache) {
    j["cache_cell_m"] = cache_cell;
    j["cache_spp"] = cache_spp;
    j["cache_direct_cells"] = cache_direct_cells;
    j["hard_spp_factor"] = hard_spp_factor;
    j["glossy_roughness"] = glossy_roughness;
    j["spread_threshold"] = spread_threshold;
    j["share_radius"] = sharing.radius;
    j["share_parallax_texels"] = sharing.parallax_texels;
    j["correct_foot"] = correct_foot;
  }
  return j;
}

nlohmann::json ProbeStats::to_json() const {
  return {{"seconds", {{"place", place_seconds}, {"cache", cache_seconds}, {"shade", shade_seconds}, {"share", share_seconds}, {"total", total_seconds}}},
          {"rays", counters.rays + placement_rays},
          {"paths", counters.paths},
          {"rays_per_second", total_seconds > 0 ? double(counters.rays + placement_rays) / total_seconds : 0.0},
          {"counts", {{"probes", probes}, {"valid", valid}, {"invalid", probes - valid}, {"nothing", nothing},
                      {"emitter", emitter}, {"transparent", transparent}, {"computed", computed_probes}}},
          {"supersampled_texels", supersampled_texels},
          {"shared_texels", shared_texels},
          {"light_texels", light_texels},
          {"light_edge_texels", light_edge_texels},
          {"negative_texels_clamped", negative_texels},
          {"foot_correction",
           {{"probes", foot_corrections},
            {"common_difference", {foot_common_difference.x, foot_common_difference.y, foot_common_difference.z}}}},
          {"cache",
           {{"cells", cache_cells},
            {"cells_with_direct_light", cache_direct_cells},
            {"cells_at_concave_edges", cache_edge_cells},
            {"edge_profiles", cache_edge_profiles},
            {"fill_samples", cache_fill_samples},
            {"fallback_lookups", cache_fallbacks}}},
          {"nonfinite_samples_caught", counters.nonfinite_samples}};
}

Image probe_image(const Image& mosaic, const ProbeLayout& layout, int i, int j) {
  Image out(layout.res_width, layout.res_height, mosaic.channels);
  for (int r = 0; r < layout.res_height; ++r)
    for (int c = 0; c < layout.res_width; ++c)
      for (int ch = 0; ch < mosaic.channels; ++ch)
        out.at(c, r, ch) = mosaic.at(j * layout.res_width + c, i * layout.res_height + r, ch);
  return out;
}

ProbeOutput render_probes(const RenderScene& scene, const CameraModel& camera, const Effects& effects,
                          const ProbeSettings& settings) {
  settings.validate();
  const auto start = Clock::now();
  std::vector<ProbeSite> sites = place_probes(scene, camera, settings.layout, settings.offset);
  const double place_seconds = seconds_since(start);
  ProbeOutput out = render_probes_at(scene, effects, std::move(sites), settings);
  out.stats.place_seconds = place_seconds;
  out.stats.placement_rays = 2 * uint64_t(settings.layout.probe_count());  // placement + gap check
  out.stats.total_seconds += place_seconds;
  return out;
}

ProbeOutput render_probes_at(const RenderScene& scene, const Effects& effects, std::vector<ProbeSite> sites,
                             const ProbeSettings& settings, const std::vector<int>& subset) {
  settings.validate();
  const ProbeLayout& layout = settings.layout;
  if (sites.size() != size_t(layout.probe_count()))
    fail("{} probe sites given for a {}x{} grid", sites.size(), layout.grid_height, layout.grid_width);
  const auto start = Clock::now();
  ProbeOutput out;
  out.layout = layout;
  out.sites = std::move(sites);
  out.mosaic = Image(layout.mosaic_width(), layout.mosaic_height(), 3);
  out.position = Image(layout.grid_width, layout.grid_height, 3);
  out.normal = Image(layout.grid_width, layout.grid_height, 3);
  out.mask = Image(layout.grid_width, layout.grid_height, 1);
  ProbeStats& stats = out.stats;

  std::vector<int> todo;
  for (int p = 0; p < layout.probe_count(); ++p) {
    const ProbeSite& s = out.sites[size_t(p)];
    const int i = p / layout.grid_width, j = p % layout.grid_width;
    ++stats.probes;
    switch (s.status) {
      case ProbeStatus::kValid: ++stats.valid; break;
      case ProbeStatus::kNothing: ++stats.nothing; break;
      case ProbeStatus::kEmitter: ++stats.emitter; break;
      case ProbeStatus::kTransparent: ++stats.transparent; break;
    }
    if (!s.computed()) continue;
    for (int c = 0; c < 3; ++c) {
      out.position.at(j, i, c) = s.origin[c];
      out.normal.at(j, i, c) = s.normal[c];
    }
    out.mask.at(j, i) = s.valid() ? 1.0f : 0.0f;
    if (subset.empty()) todo.push_back(p);
  }
  for (int p : subset) {
    if (p < 0 || p >= layout.probe_count()) fail("probe index {} outside the {}x{} grid", p, layout.grid_height, layout.grid_width);
    if (out.sites[size_t(p)].computed()) todo.push_back(p);
  }
  stats.computed_probes = todo.size();

  const uint64_t probe_seed = stream_key(settings.seed, Purpose::kProbeSeed);  // apart from color.exr's streams
  const int texels = layout.texels_per_probe();
  auto texel_id = [&](int probe, int texel) { return uint64_t(probe) * uint64_t(texels) + uint64_t(texel); };
  tbb::enumerable_thread_specific<PathCounters> local;

  // Neighbouring probes see the same scene in the same direction from points a few
  // centimetres apart: working on a tile texel by texel across its probes finds the cache
  // cells, BVH nodes and texture texels of one probe's texel still in the processor's
  // caches for the next (probe by probe, a probe's 512 texels cover the whole room first).
  const std::vector<std::vector<size_t>> tiles = probe_tiles(todo, layout.grid_width);

  // The cache: discovery from one direction per texel, then the fill.
  std::unique_ptr<RadianceCache> cache;
  if (settings.mode == ProbeMode::kCache) {
    const auto cache_start = Clock::now();
    RadianceCacheSettings cs;
    cs.cell_size = settings.cache_cell;
    cs.samples_per_cell = settings.cache_spp;
    cs.direct_distance_cells = settings.cache_direct_cells;
    cs.seed = stream_key(settings.seed, Purpose::kCacheSeed);
    cs.progress = settings.progress;
    cache = std::make_unique<RadianceCache>(scene, effects, settings.path, cs);
    tbb::enumerable_thread_specific<RadianceCache::Collector> collectors;
    // Tile by tile, texel by texel across a tile (as the shading below): neighbouring
    // probes' rays offer points to the same cells one after the other.
    tbb::parallel_for(tbb::blocked_range<size_t>(0, tiles.size(), 1), [&](const tbb::blocked_range<size_t>& r) {
      RadianceCache::Collector& collector = collectors.local();
      PathCounters& c = local.local();
      for (size_t n = r.begin(); n < r.end(); ++n) {
        for (int t = 0; t < texels; ++t) {
          for (size_t k : tiles[n]) {
            const int p = todo[k];
            const uint64_t key = item_stream_key(probe_seed, texel_id(p, t), Purpose::kProbeDiscovery);
            Rng rng(key, 0);
            const Ray ray{out.sites[size_t(p)].origin,
                          probe_texel_direction(t / layout.res_width, t % layout.res_width, layout.res_height,
                                                layout.res_width, rng.next_2d())};
            SurfaceInteraction si;
            ++c.rays;
            if (scene.trace(ray, &si) && !(si.transmission > 0.0f))
              collector.offer(*cache, cache_point(si, si.shading_normal),
                              stream_key(key, Purpose::kProbeCacheTieBreak));
          }
        }
      }
    });
    std::vector<const RadianceCache::Collector*> list;
    for (const auto& collector : collectors) list.push_back(&collector);
    PathCounters fill_counters;
    cache->build(list, &fill_counters);
    stats.counters += fill_counters;
    stats.cache_cells = cache->cell_count();
    stats.cache_direct_cells = cache->direct_cell_count();
    stats.cache_edge_cells = cache->edge_cell_count();
    stats.cache_edge_profiles = cache->edge_profile_count();
    stats.cache_fill_samples = cache->fill_samples();
    stats.cache_seconds = seconds_since(cache_start);
  }

  // The probes. A texel's spread is judged against its mean plus a floor, so that the
  // noise of nearly black texels does not flag them: kDarkFloorFraction of the mean
  // radiance a diffuse white surface would reflect under the cache's mean irradiance (a
  // scale of the view's brightness that exists before any probe is shaded).
  const float dark_floor = cache ? kDarkFloorFraction * cache->mean_irradiance_luminance() * kInvPi : 0.0f;
  const auto shade_start = Clock::now();
  const TexelEstimator estimator(scene, effects, settings, cache.get());
  const EmitterFootprints footprints(scene.scene());
  const EmitterCoverage coverage(scene.scene());
  const TexelCones cones(layout.res_height, layout.res_width);
  const bool adaptive = settings.mode == ProbeMode::kCache && settings.hard_spp_factor > 1;
  const bool share = settings.mode == ProbeMode::kCache && settings.sharing.radius > 0;
  TexelRecords records;
  tbb::enumerable_thread_specific<std::vector<std::pair<uint64_t, glm::vec3>>> emission_seen;  // sharing: added after
  if (share) {
    records.distance.assign(size_t(layout.probe_count()) * size_t(texels), std::numeric_limits<float>::infinity());
    records.samples.assign(size_t(layout.probe_count()) * size_t(texels), 0.0f);
  }
  std::atomic<uint64_t> supersampled{0}, light_texels{0}, light_edge_texels{0}, negative_texels{0};
  // Two passes when the foot correction is on (foot_correction.h): every probe's texels that
  // may look to the front, whose light measures the cache's error at each foot; then,
  // knowing the difference common to all probes, the texels facing each probe's own surface.
  const bool correct_foot = cache && settings.correct_foot;
  std::vector<FootCorrection> feet(correct_foot ? todo.size() : 0);
  glm::vec3 common_difference(0.0f);
  Progress progress("probes", todo.size() * (correct_foot ? 2 : 1), correct_foot ? "probe halves" : "probes",
                    settings.progress);
  // A probe of the tile being shaded: what its texels share.
  struct TileProbe {
    size_t k = 0;  // index into todo
    int p = 0;
    Interleave interleave;  // interleaved strata when texels are shared (probe_sharing.h)
    std::vector<uint8_t> lit;  // texels a light may cover (EmitterFootprints)
    EmitterCoverage::View lights;  // the lights' exact coverage, where `analytic`
    bool analytic = false;
    FootIrradiance measured{glm::vec3(0.0f, 0.0f, 1.0f)};
    FootCorrection foot;
  };
  auto shade_pass = [&](int pass) {
    tbb::parallel_for(
        tbb::blocked_range<size_t>(0, tiles.size(), 1),
        [&](const tbb::blocked_range<size_t>& r) {
          PathCounters& c = local.local();
          std::vector<glm::vec2> strata;
          std::vector<EmitterCoverage::View::Piece> pieces;
          std::vector<TileProbe> tile;
          uint64_t extra = 0, lit_texels = 0, edge_texels = 0, negative = 0;
          // The specular control variate's corrections can be negative on their own; a texel
          // whose mean still is (dark, grazing, few directions) is clamped to 0, and counted.
          auto clamp_at_zero = [&negative](glm::vec3* v) {
            if (glm::min(v->x, glm::min(v->y, v->z)) >= 0.0f) return;
            *v = glm::max(*v, glm::vec3(0.0f));
            ++negative;
          };
          // The texels this pass shades.
          auto in_pass = [&](const TileProbe& probe, int t) {
            return !correct_foot || (pass == 1) == cones.faces_away(t, out.sites[size_t(probe.p)].normal);
          };
          auto prepare = [&](TileProbe* probe) {
            const int p = probe->p;
            const int i = p / layout.grid_width, j = p % layout.grid_width;
            const ProbeSite& site = out.sites[size_t(p)];
            probe->interleave = Interleave();
            if (share) {
              probe->interleave.sub = sub_stratum(i, j, settings.sharing);
              probe->interleave.count = settings.sharing.window();
            }
            probe->lit.assign(size_t(texels), uint8_t(0));
            if (adaptive) footprints.mark(site.origin, layout.res_height, layout.res_width, &probe->lit);
            // The lights' exact coverage of each texel, where the emission a texel sees is the
            // lights' alone (no environment).
            probe->lights = EmitterCoverage::View();
            probe->analytic = false;
            bool any_lit = false;
            for (int t = 0; t < texels && !any_lit; ++t) any_lit = probe->lit[size_t(t)] != 0 && in_pass(*probe, t);
            if (adaptive && coverage.usable() && !effects.environment && any_lit) {
              probe->lights = coverage.view(site.origin);
              probe->analytic = probe->lights.valid();
            }
            probe->measured = FootIrradiance(site.normal);
            probe->foot = pass == 1 ? feet[probe->k].less(common_difference) : FootCorrection();
          };
          // Texel t of a probe, with lookups at its first hits through the probe's foot
          // correction; in pass 0 with the correction on, its cosine-weighted estimate goes to
          // the probe's `measured`.
          auto shade_texel = [&](TileProbe& probe, int t) {
            const int p = probe.p;
            const glm::vec3 origin = out.sites[size_t(p)].origin;
            const std::vector<uint8_t>& lit = probe.lit;
            const FootCorrection& foot = probe.foot;
            FootIrradiance* measure = pass == 0 && correct_foot ? &probe.measured : nullptr;
            const int row = t / layout.res_width, col = t % layout.res_width;
            // `count` fresh samples from sample id `first` on, stratified over the texel.
            using Part = TexelEstimator::Part;
            // `spread` (if given) receives the range of the samples' luminances; when the texel
            // is measured, cos_all and cos_emitted the sample means of the radiance and its
            // emitted part times the cosine to the probe's normal (FootIrradiance).
            float distance = std::numeric_limits<float>::infinity();
            const ProbeTexel texel(row, col, layout.res_height, layout.res_width);
            glm::vec3 cos_all(0.0f), cos_emitted(0.0f);
            auto estimate = [&](int first, int count, Part part, bool* saw_hard, float* spread = nullptr) {
              Rng permutation = item_stream(probe_seed, texel_id(p, t), Purpose::kProbeStrata, uint64_t(first));
              // The interleaving key is the same for every probe (texel and pass only).
              probe.interleave.key = item_stream_key(probe_seed, uint64_t(t), Purpose::kProbeInterleave, uint64_t(first));
              stratified_square(count, permutation, &strata, probe.interleave);
              glm::dvec3 sum(0.0), sum_cos(0.0), sum_emitted_cos(0.0);
              float lo = std::numeric_limits<float>::infinity(), hi = 0.0f;
              for (int s = 0; s < count; ++s) {
                const uint64_t key = sample_key(probe_seed, texel_id(p, t), uint64_t(first + s));
                const Ray ray{origin, texel.direction(strata[size_t(s)])};
                glm::vec3 emitted;
                glm::vec3 L = estimator.sample(ray, key, part, foot, saw_hard, &distance, &emitted, &c);
                if (!is_finite(L) || !is_finite(emitted)) {
                  ++c.nonfinite_samples;
                  L = emitted = glm::vec3(0.0f);
                }
                sum += glm::dvec3(L);
                if (measure) {
                  const double cosine = measure->cosine(ray.direction);
                  sum_cos += glm::dvec3(L) * cosine;
                  sum_emitted_cos += glm::dvec3(emitted) * cosine;
                }
                lo = std::min(lo, luminance(L));
                hi = std::max(hi, luminance(L));
              }
              if (spread) *spread = count > 0 ? hi - lo : 0.0f;
              cos_all = glm::vec3(sum_cos / double(count));
              cos_emitted = glm::vec3(sum_emitted_cos / double(count));
              return glm::vec3(sum / double(count));
            };
            // Hard texels (the first samples met a light, glass or a glossy surface, or
            // their values spread over more than spread_threshold x (their mean + a floor):
            // the texel straddles an edge or a highlight) are estimated again from
            // hard_spp_factor x spp fresh samples. Texels a light may cover
            // (EmitterFootprints) are hard from the start, and the emission seen first
            // there is estimated apart (inside the lights' coverage where it is known):
            // partial coverage of a light is the largest error otherwise. No decision looks
            // at the samples it selects, so none biases the value.
            const int spp = settings.spp, hard_spp = spp * settings.hard_spp_factor;
            bool hard = lit[size_t(t)] != 0;
            glm::vec3 value(0.0f), seen_emission(0.0f), seen_emission_cos(0.0f);
            if (!hard) {
              float spread = 0.0f;
              value = estimate(0, spp, Part::kAll, &hard, &spread);
              if (spp > 1 && spread > settings.spread_threshold * (luminance(value) + dark_floor)) hard = true;
            }
            if (hard && adaptive) {
              bool unused = false;
              if (lit[size_t(t)]) {
                value = estimate(spp, hard_spp, Part::kRest, &unused);
                const glm::vec3 rest_cos = cos_all;
                const bool edge = lit[size_t(t)] == EmitterFootprints::kEdge;
                if (probe.analytic) {
                  probe.lights.texel_pieces(row, col, layout.res_height, layout.res_width, &pieces);
                  Rng rng = item_stream(probe_seed, texel_id(p, t), Purpose::kProbeLightPart);
                  seen_emission = visible_emission(probe.lights, pieces, scene.accelerator(), origin,
                                                   spp * (edge ? kLightPartEdgeSppFactor : kLightPartSppFactor), rng,
                                                   probe.measured, &seen_emission_cos, &strata, &c.rays);
                } else {
                  seen_emission = estimate(spp + hard_spp, spp * (edge ? kEmissionEdgeSppFactor : kEmissionSppFactor),
                                           Part::kEmission, &unused);
                  seen_emission_cos = cos_emitted;
                }
                // The texel's whole light: its rest (no emission seen first) and its emission.
                cos_all = rest_cos + seen_emission_cos;
                cos_emitted = seen_emission_cos;
                edge_texels += edge;
                ++lit_texels;
              } else {
                value = estimate(spp, hard_spp, Part::kAll, &unused);
              }
              ++extra;
            }
            if (measure)
              measure->add_texel(cos_all, cos_emitted, equirect_texel_solid_angle(row, layout.res_width, layout.res_height));
            clamp_at_zero(&value);
            if (share) {
              records.distance[size_t(texel_id(p, t))] = distance;
              records.samples[size_t(texel_id(p, t))] = float(hard && adaptive ? hard_spp : spp);
              // Emission seen directly is not shared: a light's edge moves across a texel
              // with the slightest parallax, and its own directions already resolve it.
              if (lit[size_t(t)]) emission_seen.local().push_back({texel_id(p, t), seen_emission});
            } else {
              value += seen_emission;
            }
            const glm::ivec2 at = layout.mosaic_pixel(p, t);
            for (int ch = 0; ch < 3; ++ch) out.mosaic.at(at.x, at.y, ch) = value[ch];
          };
          for (size_t n = r.begin(); n < r.end(); ++n) {
            tile.resize(tiles[n].size());
            for (size_t m = 0; m < tile.size(); ++m) {
              tile[m].k = tiles[n][m];
              tile[m].p = todo[tiles[n][m]];
              prepare(&tile[m]);
            }
            for (int t = 0; t < texels; ++t)
              for (TileProbe& probe : tile)
                if (in_pass(probe, t)) shade_texel(probe, t);
            if (pass == 0 && correct_foot)
              for (const TileProbe& probe : tile)
                feet[probe.k] = FootCorrection::measure(*cache, out.sites[size_t(probe.p)], probe.measured);
            progress.advance(tile.size());
          }
          supersampled += extra;
          light_texels += lit_texels;
          light_edge_texels += edge_texels;
          negative_texels += negative;
        },
        tbb::simple_partitioner());
  };
  shade_pass(0);
  if (correct_foot) {
    // The common difference is a mean over the probes: with few of them it would take most
    // of each probe's own difference with it, so then none is corrected.
    const size_t active =
        size_t(std::count_if(feet.begin(), feet.end(), [](const FootCorrection& f) { return f.active(); }));
    if (active < kMinFootCorrections) std::fill(feet.begin(), feet.end(), FootCorrection());
    common_difference = FootCorrection::common_difference(feet);
    stats.foot_corrections = active < kMinFootCorrections ? 0 : active;
    stats.foot_common_difference = common_difference;
    shade_pass(1);
  }
  progress.finish();
  for (const PathCounters& c : local) stats.counters += c;
  stats.supersampled_texels = supersampled.load();
  stats.light_texels = light_texels.load();
  stats.light_edge_texels = light_edge_texels.load();
  stats.negative_texels = negative_texels.load();
  if (cache) stats.cache_fallbacks = cache->fallbacks();
  stats.shade_seconds = seconds_since(shade_start);
  if (share) {
    const auto share_start = Clock::now();
    std::vector<uint8_t> computed(size_t(layout.probe_count()), 0);
    for (int p : todo) computed[size_t(p)] = 1;
    out.mosaic = share_between_neighbours(out.mosaic, layout, out.sites, computed, records, settings.sharing,
                                          &stats.shared_texels);
    for (const auto& list : emission_seen) {
      for (const auto& [id, emission] : list) {
        const glm::ivec2 at = layout.mosaic_pixel(int(id / uint64_t(texels)), int(id % uint64_t(texels)));
        for (int ch = 0; ch < 3; ++ch) out.mosaic.at(at.x, at.y, ch) += emission[ch];
      }
    }
    stats.share_seconds = seconds_since(share_start);
  }
  stats.total_seconds = seconds_since(start);
  return out;
}

}  // namespace phyir::render
